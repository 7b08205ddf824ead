// Planted violation: dynamic_cast needs RTTI.
struct Animal {
  virtual int legs() const { return 4; }

 protected:
  ~Animal() {}
};
struct Bird : Animal {
  int legs() const { return 2; }
};

bool is_bird(Animal* a) { return dynamic_cast<Bird*>(a) != 0; }  // expect: rtti
