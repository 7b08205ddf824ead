// Planted violation: in-class member initialiser, in a header.
#ifndef TESTDATA_MEMBER_INITIALIZER_H
#define TESTDATA_MEMBER_INITIALIZER_H

#include <stdint.h>  // uint16_t

struct Counter {
  uint16_t count = 0;  // expect: member-initializer
};

#endif
