// Planted violation: range-based for.
int sum() {
  int values[3] = {1, 2, 3};
  int total = 0;
  for (int v : values) total += v;  // expect: range-for
  return total;
}
