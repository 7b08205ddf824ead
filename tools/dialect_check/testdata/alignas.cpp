// Planted violation: alignas and alignof.
struct alignas(4) Packet {  // expect: alignas-alignof
  char bytes[6];
};

unsigned packet_alignment() { return alignof(Packet); }  // expect: alignas-alignof
