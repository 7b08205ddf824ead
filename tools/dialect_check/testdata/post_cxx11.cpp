// Planted violation: C++14/17 features.
auto deduced() { return 3; }  // expect: post-cxx11
static_assert(sizeof(int) == 2);  // expect: post-cxx11
