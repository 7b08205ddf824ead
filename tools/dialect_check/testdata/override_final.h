// Planted violation: override and final (contextual keywords, found in the AST).
#ifndef TESTDATA_OVERRIDE_FINAL_H
#define TESTDATA_OVERRIDE_FINAL_H

class Shape {
 public:
  virtual int area() const = 0;

 protected:
  ~Shape() {}
};

class Square final : public Shape {  // expect: override-final
 public:
  int area() const override { return 4; }  // expect: override-final
};

#endif
