// The play loop's logic. Every event, live or scripted, goes through Apply right before its step
// is simulated, which turns it into the world point it acts on and records exactly that point:
// replay cannot depend on window size, camera fitting or rounding of pixels.
#include "game/play_controller.h"

#include <algorithm>

namespace game {

PlayController::PlayController(Scene scene, std::vector<InputEvent> script, int image_width,
                               int image_height, PlayLimits limits, double max_frame_seconds,
                               FilmView view)
    : scene_(std::move(scene)),
      script_(std::move(script)),
      image_width_(image_width),
      image_height_(image_height),
      limits_(limits),
      // The session gets no events: this class applies them, so it can record each one.
      view_(view),
      session_(std::make_unique<Session>(scene_, std::vector<InputEvent>{}, image_width,
                                         image_height)),
      camera_(view_.camera.value_or(session_->View()), view_.follow, session_->World()),
      clock_(session_->World().Def().dt, max_frame_seconds) {
  KeepRewindPoint();
}

bool PlayController::Finished() const {
  return limits_.stop_at && session_->StepIndex() >= *limits_.stop_at;
}

bool PlayController::PauseDue() const {
  return limits_.pause_at && !pause_at_done_ && session_->StepIndex() == *limits_.pause_at;
}

int PlayController::Advance(double frame_seconds) {
  if (PauseDue()) {
    paused_ = true;
    pause_at_done_ = true;
  }
  if (paused_ || Finished()) {
    // Time spent paused is not owed: resuming must not burst through a backlog of steps.
    clock_.Reset();
    return 0;
  }
  const int due = clock_.Advance(frame_seconds);
  int taken = 0;
  while (taken < due && !Finished()) {
    StepOne();
    ++taken;
    if (PauseDue()) {
      paused_ = true;
      pause_at_done_ = true;
      break;
    }
  }
  if (taken < due) clock_.Reset();
  return taken;
}

void PlayController::Click(engine::Vec2 p) { Queue(EventKind::kClickWorld, p); }
void PlayController::Grab(engine::Vec2 p) { Queue(EventKind::kGrabWorld, p); }
void PlayController::Drag(engine::Vec2 p) { Queue(EventKind::kDragWorld, p); }
void PlayController::Release() { Queue(EventKind::kRelease, {}); }

void PlayController::Queue(EventKind kind, engine::Vec2 p) {
  if (Finished()) return;
  // A target set twice before a step acts as the last one alone: keep one drag, not hundreds.
  if (kind == EventKind::kDragWorld && !pending_.empty() &&
      pending_.back().kind == EventKind::kDragWorld) {
    pending_.back().at = p;
    return;
  }
  pending_.push_back(InputEvent{0, kind, p});
}

std::size_t PlayController::PendingClicks() const {
  return static_cast<std::size_t>(std::count_if(
      pending_.begin(), pending_.end(), [](const InputEvent& e) { return IsClick(e.kind); }));
}

void PlayController::TogglePause() {
  paused_ = !paused_;
  clock_.Reset();
}

bool PlayController::StepOnce() {
  if (!paused_ || Finished()) return false;
  StepOne();
  return true;
}

Status PlayController::LoadState(const std::string& path) {
  if (Status refused = session_->LoadState(path)) return refused;
  while (next_script_event_ < script_.size() && script_[next_script_event_].step < session_->StepIndex()) {
    ++next_script_event_;
  }
  camera_ = FilmCamera(view_.camera.value_or(session_->View()), view_.follow, session_->World());
  rewind_points_.clear();
  rewind_bytes_ = 0;
  KeepRewindPoint();
  return std::nullopt;
}

void PlayController::Restart() {
  session_ = std::make_unique<Session>(scene_, std::vector<InputEvent>{}, image_width_,
                                       image_height_);
  camera_ = FilmCamera(view_.camera.value_or(session_->View()), view_.follow, session_->World());
  next_script_event_ = 0;
  pending_.clear();
  recorded_.clear();
  clock_.Reset();
  rewind_points_.clear();
  rewind_bytes_ = 0;
  KeepRewindPoint();
}

void PlayController::StepOne() {
  // As Session::Step does with its own events: everything due at or before this step first.
  while (next_script_event_ < script_.size() &&
         script_[next_script_event_].step <= session_->StepIndex()) {
    Apply(script_[next_script_event_++]);
  }
  for (InputEvent& event : pending_) {
    event.step = session_->StepIndex();
    Apply(event);
  }
  pending_.clear();
  session_->Step();
  camera_.Advance(session_->World());
  if (session_->StepIndex() % kRewindEvery == 0) KeepRewindPoint();
}

void PlayController::KeepRewindPoint() {
  RewindPoint point{session_->StepIndex(), session_->World().TakeSnapshot()};
  rewind_bytes_ += point.snapshot.size();
  rewind_points_.push_back(std::move(point));
  // Bounded memory: the oldest points go first, but one is always kept.
  while (rewind_bytes_ > kRewindBytes && rewind_points_.size() > 1) {
    rewind_bytes_ -= rewind_points_.front().snapshot.size();
    rewind_points_.pop_front();
  }
}

bool PlayController::Rewind() {
  const std::int64_t now = session_->StepIndex();
  // Points at or after the current step belong to a future that is being undone.
  while (!rewind_points_.empty() && rewind_points_.back().step >= now) {
    rewind_bytes_ -= rewind_points_.back().snapshot.size();
    rewind_points_.pop_back();
  }
  if (rewind_points_.empty()) {
    KeepRewindPoint();  // at the oldest point already: stay, and keep it
    return false;
  }
  const RewindPoint& point = rewind_points_.back();
  session_->Rewind(point.snapshot);
  std::erase_if(recorded_, [&](const InputEvent& e) { return e.step >= point.step; });
  next_script_event_ = 0;
  while (next_script_event_ < script_.size() && script_[next_script_event_].step < point.step) ++next_script_event_;
  pending_.clear();
  camera_ = FilmCamera(view_.camera.value_or(session_->View()), view_.follow, session_->World());
  return true;
}

std::vector<std::int64_t> PlayController::RewindSteps() const {
  std::vector<std::int64_t> steps;
  for (const RewindPoint& p : rewind_points_) steps.push_back(p.step);
  return steps;
}

render::Camera PlayController::Camera() const {
  return camera_.For(session_->ImageWidth(), session_->ImageHeight());
}

void PlayController::Apply(const InputEvent& event) {
  // The session maps a pixel click as it maps a script's, so the point is bit-identical.
  const engine::Vec2 p = session_->ApplyEvent(event);
  recorded_.push_back(InputEvent{session_->StepIndex(), WorldKind(event.kind), p});
}

EventsAfterEnd PlayController::EventsLeft() const {
  EventsAfterEnd late;
  late.count = script_.size() - next_script_event_ + pending_.size();
  late.first_step = session_->StepIndex();
  if (next_script_event_ < script_.size()) late.first_step = script_[next_script_event_].step;
  late.end_step = session_->StepIndex();
  return late;
}

}  // namespace game
