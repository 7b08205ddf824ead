// Planted violation: code that only compiles where int is 32 bits (int is 16 on the target).
static_assert(sizeof(int) == 4, "assumes 32-bit int");  // expect: compile-error
