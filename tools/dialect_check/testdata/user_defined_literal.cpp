// Planted violation: a user-defined literal.
long operator"" _mm(unsigned long long v) { return static_cast<long>(v * 1000); }  // expect: user-defined-literal
