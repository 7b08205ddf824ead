// Planted violation: exceptions (rejected by -fno-exceptions).
int checked(int v) {
  if (v < 0) throw 1;  // expect: exceptions
  return v;
}
