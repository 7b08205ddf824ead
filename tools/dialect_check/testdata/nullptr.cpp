// Planted violation: nullptr.
int* pick(int* p) {
  if (p == nullptr) return 0;  // expect: nullptr
  return p;
}
