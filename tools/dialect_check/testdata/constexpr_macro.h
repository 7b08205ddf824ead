// Planted violation: constexpr hidden in a macro (reported at the #define and at the use).
#ifndef TESTDATA_CONSTEXPR_MACRO_H
#define TESTDATA_CONSTEXPR_MACRO_H

#define COMPILE_TIME constexpr  // expect: constexpr

COMPILE_TIME int kHidden = 3;  // expect: constexpr

#endif
