// Planted violation: an enum declared before it is defined (opaque enum declaration).
#ifndef TESTDATA_OPAQUE_ENUM_H
#define TESTDATA_OPAQUE_ENUM_H

enum class Mode : unsigned char;  // expect: opaque-enum

#endif
