// Sequence classification: new, duplicate, pending, ahead, out of window; wrap at 256.
#include "firmware/protocol/sequence_window.h"

#include <gtest/gtest.h>

namespace {

using proto::RealtimeSequence;
using proto::SeqClass;
using proto::SequenceWindow;

TEST(SequenceWindow, ExpectedSeqIsNewAndAcceptAdvances) {
  SequenceWindow w;
  w.reset(10);
  EXPECT_EQ(SeqClass::kNew, w.classify(10));
  w.accept(10);
  EXPECT_EQ(11, w.next_expected());
  EXPECT_EQ(10, w.last_accepted());
}

TEST(SequenceWindow, AcceptedFramesWithinEightBehindAreDuplicates) {
  SequenceWindow w;
  w.reset(100);
  for (int s = 100; s < 120; ++s) w.accept(static_cast<uint8_t>(s));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(119));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(112));    // 8 behind next (120)
  EXPECT_EQ(SeqClass::kOutOfWindow, w.classify(111));  // 9 behind
}

TEST(SequenceWindow, UpToSevenAheadIsAGapBeyondIsOutOfWindow) {
  SequenceWindow w;
  w.reset(50);
  EXPECT_EQ(SeqClass::kAhead, w.classify(51));
  EXPECT_EQ(SeqClass::kAhead, w.classify(57));
  EXPECT_EQ(SeqClass::kOutOfWindow, w.classify(58));
  EXPECT_EQ(SeqClass::kOutOfWindow, w.classify(200));
}

TEST(SequenceWindow, WrapsFrom255To0) {
  SequenceWindow w;
  w.reset(254);
  w.accept(254);
  w.accept(255);
  EXPECT_EQ(0, w.next_expected());
  EXPECT_EQ(SeqClass::kNew, w.classify(0));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(255));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(254));
  EXPECT_EQ(SeqClass::kAhead, w.classify(3));
  w.accept(0);
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(0));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(249));  // 8 behind next (1)
  EXPECT_EQ(SeqClass::kOutOfWindow, w.classify(248));
}

TEST(SequenceWindow, AcceptOfAnUnexpectedSeqChangesNothing) {
  SequenceWindow w;
  w.reset(5);
  w.accept(7);
  w.accept(4);
  EXPECT_EQ(5, w.next_expected());
}

TEST(SequenceWindow, HeldFrameClassifiesAsPendingUntilAccepted) {
  SequenceWindow w;
  w.reset(9);
  w.mark_pending(9);
  EXPECT_TRUE(w.pending());
  EXPECT_EQ(SeqClass::kPending, w.classify(9));
  EXPECT_EQ(SeqClass::kAhead, w.classify(10));
  w.accept(9);
  EXPECT_FALSE(w.pending());
  EXPECT_EQ(SeqClass::kNew, w.classify(10));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(9));
}

TEST(SequenceWindow, MarkPendingIgnoresAnythingButTheExpectedSeq) {
  SequenceWindow w;
  w.reset(9);
  w.mark_pending(10);
  EXPECT_FALSE(w.pending());
}

TEST(SequenceWindow, ClearPendingMakesTheHeldSeqNewAgain) {
  SequenceWindow w;
  w.reset(9);
  w.mark_pending(9);
  w.clear_pending();
  EXPECT_EQ(SeqClass::kNew, w.classify(9));
}

TEST(SequenceWindow, ResetStartsOverAtTheGivenSeqAndDropsPending) {
  SequenceWindow w;
  w.reset(1);
  w.mark_pending(1);
  w.reset(200);
  EXPECT_FALSE(w.pending());
  EXPECT_EQ(SeqClass::kNew, w.classify(200));
  EXPECT_EQ(SeqClass::kDuplicate, w.classify(199));
}

TEST(SequenceWindow, EveryOneOf256SeqsHasExactlyOneClass) {
  // Counting the classes over the whole space pins the window sizes: 1 new, 8 duplicate
  // behind, 7 ahead, 240 out of window.
  SequenceWindow w;
  w.reset(0);
  int counts[6] = {0, 0, 0, 0, 0, 0};
  for (int s = 0; s < 256; ++s) ++counts[static_cast<int>(w.classify(static_cast<uint8_t>(s)))];
  EXPECT_EQ(1, counts[static_cast<int>(SeqClass::kNew)]);
  EXPECT_EQ(8, counts[static_cast<int>(SeqClass::kDuplicate)]);
  EXPECT_EQ(7, counts[static_cast<int>(SeqClass::kAhead)]);
  EXPECT_EQ(240, counts[static_cast<int>(SeqClass::kOutOfWindow)]);
}

TEST(RealtimeSequence, FirstFrameIsNewWhateverItsSeq) {
  RealtimeSequence r;
  EXPECT_EQ(SeqClass::kNew, r.classify(77));
}

TEST(RealtimeSequence, SameSeqAgainIsADuplicate) {
  RealtimeSequence r;
  r.accept(5);
  EXPECT_EQ(SeqClass::kDuplicate, r.classify(5));
}

TEST(RealtimeSequence, NewerSeqsUpTo127AheadAreNewEvenWithGaps) {
  RealtimeSequence r;
  r.accept(5);
  EXPECT_EQ(SeqClass::kNew, r.classify(6));
  EXPECT_EQ(SeqClass::kNew, r.classify(9));  // 7 and 8 were lost: no gap rule
  EXPECT_EQ(SeqClass::kNew, r.classify(132));
  EXPECT_EQ(SeqClass::kStale, r.classify(133));
}

TEST(RealtimeSequence, OlderSeqIsStaleSoALateResumeCannotUndoAHold) {
  RealtimeSequence r;
  r.accept(10);  // #R
  r.accept(11);  // #H
  EXPECT_EQ(SeqClass::kStale, r.classify(10));
}

TEST(RealtimeSequence, WrapsFrom255To0) {
  RealtimeSequence r;
  r.accept(255);
  EXPECT_EQ(SeqClass::kNew, r.classify(0));
  r.accept(0);
  EXPECT_EQ(SeqClass::kStale, r.classify(255));
}

TEST(RealtimeSequence, ResetForgetsTheLastSeq) {
  RealtimeSequence r;
  r.accept(100);
  r.reset();
  EXPECT_EQ(SeqClass::kNew, r.classify(50));
}

}  // namespace
