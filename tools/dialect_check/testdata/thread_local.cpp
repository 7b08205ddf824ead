// Planted violation: thread_local storage.
thread_local int per_thread_counter;  // expect: thread-local
