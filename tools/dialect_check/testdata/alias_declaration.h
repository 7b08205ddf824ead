// Planted violation: alias declaration and alias template.
#ifndef TESTDATA_ALIAS_DECLARATION_H
#define TESTDATA_ALIAS_DECLARATION_H

using Micrometres = long;  // expect: alias-declaration

template <class T>
using Pointer = T*;  // expect: alias-declaration

#endif
