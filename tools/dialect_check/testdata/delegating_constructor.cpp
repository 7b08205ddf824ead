// Planted violation: a constructor that delegates to another.
struct Span {
  Span(int begin, int end) : begin_(begin), end_(end) {}
  Span() : Span(0, 0) {}  // expect: delegating-constructor
  int begin_;
  int end_;
};

int empty_span_length() {
  Span s;
  return s.end_ - s.begin_;
}
