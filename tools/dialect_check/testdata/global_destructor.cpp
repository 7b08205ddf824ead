// Planted violation: a global object whose destructor would run at exit.
struct Logger {
  ~Logger() { ++closed; }
  int closed;
};

Logger global_logger;  // expect: global-destructor
