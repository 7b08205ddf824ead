// Planted violation: noexcept specifier.
int quiet(int v) noexcept { return v + 1; }  // expect: noexcept
