// Planted violation: a ref-qualified member function.
struct Buffer {
  int take() && { return 1; }  // expect: ref-qualifier
};
