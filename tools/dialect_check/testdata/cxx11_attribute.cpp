// Planted violation: [[attribute]] syntax.
[[noreturn]] void stop();  // expect: cxx11-attribute

void halt() { stop(); }
