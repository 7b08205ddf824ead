// Planted violation: inheriting constructors.
struct Base {
  explicit Base(int v) : value(v) {}
  int value;
};

struct Derived : Base {
  using Base::Base;  // expect: inheriting-constructor
};

int make() { return Derived(3).value; }
