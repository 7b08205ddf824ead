// Single-producer/single-consumer ring of fixed power-of-two capacity: the only way the
// ISRs and the background loop share data. No locks, no heap.
#ifndef FIRMWARE_CORE_SPSC_RING_H
#define FIRMWARE_CORE_SPSC_RING_H

#include <stdint.h>  // uint16_t

namespace core {

// Compiler barrier: stops the compiler from moving memory accesses across it. It emits
// no instruction.
#define CORE_SPSC_BARRIER() __asm__ __volatile__("" ::: "memory")

// Memory-ordering contract.
// - head_ is written only by the producer, tail_ only by the consumer. Both are free-
//   running 16-bit counters (size = head - tail modulo 2^16), so a full ring is told
//   from an empty one without a spare slot; kCapacity <= 32768 keeps that unambiguous.
// - On the dsPIC (and any 16-bit target) a 16-bit aligned store/load is a single
//   instruction, hence atomic with respect to an interrupt. On the AVR proxy it is two
//   byte accesses; there the ring is used in one context only (tests), or the caller
//   must mask the interrupt around the other side's index read.
// - The producer writes the slot, then a compiler barrier, then publishes head_. The
//   consumer reads head_, barrier, reads the slot, barrier, then publishes tail_. On a
//   single core (the target) program order is all that is needed, and the barrier
//   forces it on the compiler. On an x86 host (two-thread stress test) the hardware
//   model is TSO: stores become visible in program order and loads are not reordered
//   with older loads, nor stores with older loads, so the compiler barrier is
//   sufficient there as well. (On weakly ordered hosts such as ARM this would need real
//   fences; portable code cannot use std::atomic, and the host test is x86-only.)
template <typename T, uint16_t kCapacity>
class SpscRing {
  static_assert(kCapacity >= 2 && kCapacity <= 32768U, "capacity 2..32768");
  static_assert((kCapacity & (kCapacity - 1)) == 0, "capacity must be a power of two");

 public:
  SpscRing() : head_(0), tail_(0) {}

  // Producer: appends v; false (and nothing stored) when full.
  bool push(const T& v) {
    const uint16_t head = head_;
    const uint16_t tail = tail_;
    if ((uint16_t)(head - tail) >= kCapacity) return false;
    slot_[head & kMask] = v;
    CORE_SPSC_BARRIER();  // the element is written before it is published
    head_ = (uint16_t)(head + 1);
    return true;
  }

  // Producer: the slot the next commit() publishes, written in place (no copy of a whole
  // element through the producer's stack); 0 when full. The consumer sees nothing of it
  // before commit(); a reserve() without a commit() publishes nothing.
  T* reserve() {
    const uint16_t head = head_;
    if ((uint16_t)(head - tail_) >= kCapacity) return 0;
    return &slot_[head & kMask];
  }

  // Producer: publishes the slot reserve() gave (which must not have returned 0).
  void commit() {
    CORE_SPSC_BARRIER();  // the element is written before it is published
    head_ = (uint16_t)(head_ + 1);
  }

  // Consumer: removes the oldest element into *out; false when empty.
  bool pop(T* out) {
    const uint16_t tail = tail_;
    const uint16_t head = head_;
    if (head == tail) return false;
    CORE_SPSC_BARRIER();  // read the slot only after seeing head_
    *out = slot_[tail & kMask];
    CORE_SPSC_BARRIER();  // the slot is read before it is handed back
    tail_ = (uint16_t)(tail + 1);
    return true;
  }

  // Consumer: element at offset from the oldest (0 = oldest), 0 if offset >= size().
  // Valid until the consumer pops past it.
  const T* peek(uint16_t offset) const {
    const uint16_t tail = tail_;
    const uint16_t head = head_;
    if (offset >= (uint16_t)(head - tail)) return 0;
    CORE_SPSC_BARRIER();
    return &slot_[(uint16_t)(tail + offset) & kMask];
  }

  // Producer: the k-th newest element (0 = newest), 0 if k >= size(). The slot stays the
  // producer's to update in place until it pushes again (it cannot be reused before); the
  // consumer may read it meanwhile, so only single stores the consumer tolerates.
  T* newest(uint16_t k) {
    const uint16_t head = head_;
    const uint16_t tail = tail_;
    if (k >= (uint16_t)(head - tail)) return 0;
    return &slot_[(uint16_t)(head - 1U - k) & kMask];
  }

  // Elements stored (either side; a snapshot).
  uint16_t size() const { return (uint16_t)(head_ - tail_); }

  // Slots free (either side; a snapshot).
  uint16_t free_space() const { return (uint16_t)(kCapacity - size()); }

  bool empty() const { return head_ == tail_; }

  bool full() const { return size() >= kCapacity; }

  // Consumer: drops everything stored (the producer may keep pushing meanwhile).
  void clear() {
    const uint16_t head = head_;
    CORE_SPSC_BARRIER();
    tail_ = head;
  }

  static uint16_t capacity() { return kCapacity; }

 private:
  enum { kMask = kCapacity - 1 };
  volatile uint16_t head_;  // next slot to write; producer-owned
  volatile uint16_t tail_;  // next slot to read; consumer-owned
  T slot_[kCapacity];
};

}  // namespace core

#endif  // FIRMWARE_CORE_SPSC_RING_H
