// Planted violation: heap allocation with new/delete and malloc/free.
#include <stddef.h>  // size_t

extern "C" void* malloc(size_t bytes);
extern "C" void free(void* p);

int heap_round_trip() {
  int* a = new int(3);  // expect: heap
  int v = *a;
  delete a;  // expect: heap
  void* b = malloc(4);  // expect: heap
  free(b);  // expect: heap
  return v;
}
