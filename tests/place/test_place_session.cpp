// The placement session's worker (src/place/place_session.h) with a field whose answers wait
// behind a gate, so the order of events is fixed: a level 0 under way when the state moves on
// is finished and served for its revision; a revision whose level 0 never started is stale at
// once, and so is every other image of an older revision.
#include <gtest/gtest.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>

#include "core/output_file.h"
#include "field_files/field_factory.h"
#include "place/place_session.h"

using namespace inim;
using namespace std::chrono_literals;

namespace {

// The ramp scene behind a gate: each query takes a ticket (1, 2, ...) as it begins and waits
// until its ticket is let through, so the test decides which renders finish and when.
class GatedField : public Field {
 public:
  explicit GatedField(std::unique_ptr<Field> inner) : inner_(std::move(inner)) {}
  FieldEncoding encoding() const override { return inner_->encoding(); }
  std::string colorSpace() const override { return inner_->colorSpace(); }
  void bounds(Point3& lo, Point3& hi) const override { inner_->bounds(lo, hi); }
  void query(std::span<const FieldRay> rays, std::span<const SampledWavelengths> lambda, std::span<FieldSample> out,
             uint64_t seed) const override {
    std::unique_lock<std::mutex> lock(m_);
    const int ticket = ++begun_;
    cv_.notify_all();
    cv_.wait(lock, [&] { return open_ || ticket <= letThrough_; });
    lock.unlock();
    inner_->query(rays, lambda, out, seed);
  }
  // Open: every query passes. Shut: the queries begun so far pass, later ones wait.
  void setOpen(bool open) {
    std::lock_guard<std::mutex> lock(m_);
    open_ = open;
    letThrough_ = begun_;
    cv_.notify_all();
  }
  // Shut, letting exactly the next n tickets through (begun or not).
  void letNextThrough(int n) {
    std::lock_guard<std::mutex> lock(m_);
    letThrough_ += n;
    cv_.notify_all();
  }
  // Waits until more than `n` queries have begun; the number begun.
  int waitBegunOver(int n) {
    std::unique_lock<std::mutex> lock(m_);
    cv_.wait_for(lock, 30s, [&] { return begun_ > n; });
    return begun_;
  }

 private:
  std::unique_ptr<Field> inner_;
  mutable std::mutex m_;
  mutable std::condition_variable cv_;
  mutable int begun_ = 0;
  int letThrough_ = 0;
  bool open_ = false;
};

struct GatedSession {
  GatedField* gate = nullptr;
  std::unique_ptr<PlaceSession> session;
  GatedSession() {
    LoadedField f = loadField(dataPath("scenes/test/depth-ramp.json"), "scene");
    auto gated = std::make_unique<GatedField>(std::move(f.field));
    gate = gated.get();
    f.field = std::move(gated);
    f.analyticScene = nullptr;
    PlaceOptions o;
    o.outDir = (std::filesystem::temp_directory_path() / "inim-test-place-session").string();
    o.quietMs = 600000;  // no level 1 or 2 during the test
    session = std::make_unique<PlaceSession>(o, std::move(f));
  }
  ~GatedSession() { gate->setOpen(true); }  // the worker may be waiting at the gate
  uint64_t move(double tz) {
    return session->putState(R"({"placement": {"translate_mm": [0, 0, )" + std::to_string(tz) + "]}}")["revision"];
  }
  ImageAnswer::Status status(ImageKind k, uint64_t rev) { return session->image(k, rev, 20s).status; }
  // Revision 0 shown whole (level 0 and diagram), then a move whose level 0 waits at the shut
  // gate; the move's revision.
  uint64_t showThenHoldAMove(double tz) {
    gate->setOpen(true);
    EXPECT_EQ(status(ImageKind::Level0, 0), ImageAnswer::Status::Ready);
    EXPECT_EQ(status(ImageKind::Diagram, 0), ImageAnswer::Status::Ready);
    gate->setOpen(false);
    queriesPerLevel0 = gate->waitBegunOver(-1);  // only revision 0's level 0 has queried
    const uint64_t r = move(tz);
    gate->waitBegunOver(queriesPerLevel0);
    return r;
  }
  // Lets the held level 0 finish while any later one stays at the gate: a level 0 asks the
  // same number of queries whatever the placement (fixed rays, fixed chunks).
  void finishTheHeldLevel0() { gate->letNextThrough(queriesPerLevel0); }
  int queriesPerLevel0 = 0;
};

using S = ImageAnswer::Status;

}  // namespace

TEST(PlaceSession, ALevel0UnderWayIsFinishedAndServedAfterTheStateMovesOn) {
  GatedSession g;
  const uint64_t r1 = g.showThenHoldAMove(1.0);  // level 0 of r1 is waiting at the gate
  const uint64_t r2 = g.move(2.0);
  g.finishTheHeldLevel0();
  const ImageAnswer a1 = g.session->image(ImageKind::Level0, r1, 20s);
  EXPECT_EQ(a1.status, S::Ready) << a1.error;
  EXPECT_EQ(a1.revision, r1);
  EXPECT_EQ(a1.png.substr(1, 3), "PNG");
  g.gate->setOpen(true);
  EXPECT_EQ(g.status(ImageKind::Level0, r2), S::Ready);
  // Everything else of r1 is stale, as is its level 0 once a newer one is kept.
  EXPECT_EQ(g.status(ImageKind::Diagram, r1), S::Stale);
  EXPECT_EQ(g.status(ImageKind::Level1, r1), S::Stale);
  EXPECT_EQ(g.status(ImageKind::Level0, r1), S::Stale);
}

// The diagram, drawn by its own thread from a revision's level 0, is kept for that revision
// like level 0: still served once the state has moved on, until a newer diagram replaces it.
TEST(PlaceSession, AFinishedDiagramIsServedForItsRevisionUntilANewerOne) {
  GatedSession g;
  const uint64_t r1 = g.showThenHoldAMove(1.0);  // no diagram of r1 can begin
  const ImageAnswer d0 = g.session->image(ImageKind::Diagram, 0, 20s);
  EXPECT_EQ(d0.status, S::Ready) << d0.error;
  EXPECT_EQ(d0.revision, 0u);
  EXPECT_EQ(d0.png.substr(1, 3), "PNG");
  g.gate->setOpen(true);
  EXPECT_EQ(g.status(ImageKind::Diagram, r1), S::Ready);
  EXPECT_EQ(g.status(ImageKind::Diagram, 0), S::Stale);
}

TEST(PlaceSession, ARevisionWhoseLevel0NeverStartedIsStaleAtOnce) {
  GatedSession g;
  const uint64_t r1 = g.showThenHoldAMove(1.0);
  const uint64_t r2 = g.move(2.0), r3 = g.move(3.0);
  EXPECT_EQ(g.status(ImageKind::Level0, r2), S::Stale);  // superseded before it began
  g.finishTheHeldLevel0();
  EXPECT_EQ(g.status(ImageKind::Level0, r1), S::Ready);
  EXPECT_EQ(g.status(ImageKind::Level0, r2), S::Stale);
  g.gate->setOpen(true);
  EXPECT_EQ(g.status(ImageKind::Level0, r3), S::Ready);
  EXPECT_EQ(g.status(ImageKind::Diagram, r3), S::Ready);
  EXPECT_EQ(g.status(ImageKind::Diagram, r1), S::Stale);
}

// The diagram is drawn only for a revision a request asked for: a drag's revisions that no one
// asks about cost no drawing. (Revision 0's is asked for first: it may be drawn at start, and
// would otherwise still be drawing, under load, when the count is read.)
TEST(PlaceSession, ADiagramIsDrawnOnlyOnceAskedFor) {
  GatedSession g;
  g.gate->setOpen(true);
  EXPECT_EQ(g.status(ImageKind::Diagram, 0), S::Ready);
  const uint64_t r1 = g.move(1.0), r2 = g.move(2.0);
  EXPECT_EQ(g.status(ImageKind::Level0, r2), S::Ready);
  std::this_thread::sleep_for(300ms);  // time enough for an unasked diagram to be drawn
  const auto drawn = [&] { return g.session->latency()["diagram"]["count"].get<int>(); };
  const int before = drawn();
  EXPECT_EQ(before, 1);
  EXPECT_EQ(g.status(ImageKind::Diagram, r1), S::Stale);  // older, and never drawn
  EXPECT_EQ(g.status(ImageKind::Diagram, r2), S::Ready);
  EXPECT_EQ(drawn(), before + 1);
}
