// Planted violation: a virtual destructor (pulls in operator delete).
#ifndef TESTDATA_VIRTUAL_DESTRUCTOR_H
#define TESTDATA_VIRTUAL_DESTRUCTOR_H

class Port {
 public:
  virtual ~Port() {}  // expect: virtual-destructor
  virtual void write(unsigned char byte) = 0;
};

#endif
