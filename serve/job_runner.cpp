#include "serve/job_runner.h"

#include <exception>

namespace exacity::serve {

const char* state_name(JobState state) {
  switch (state) {
    case JobState::Idle:
      return "idle";
    case JobState::Running:
      return "running";
    case JobState::Done:
      return "done";
    case JobState::Failed:
      return "failed";
    case JobState::Cancelled:
      return "cancelled";
  }
  return "idle";
}

nlohmann::json JobStatus::to_json() const {
  nlohmann::json j;
  j["state"] = state_name(state);
  j["job"] = job.empty() ? nlohmann::json() : nlohmann::json(job);
  j["stage"] = stage.empty() ? nlohmann::json() : nlohmann::json(stage);
  j["index"] = index;
  j["count"] = count;
  j["fraction"] = fraction;
  j["error"] = state == JobState::Failed || state == JobState::Cancelled ? nlohmann::json(error) : nlohmann::json();
  j["answered"] = answered;
  return j;
}

void JobRunner::Progress::stage(int index, int count, const std::string& name) {
  runner_.check_cancelled();
  std::lock_guard lock(runner_.mutex_);
  JobStatus& s = runner_.status_;
  s.stage = name, s.index = index, s.count = count, s.fraction = 0;
  percent_ = -1;
  runner_.publish("stage", {{"job", s.job}, {"stage", name}, {"index", index}, {"count", count}});
}

void JobRunner::Progress::fraction(const std::string& name, double done) {
  runner_.check_cancelled();
  // Whole percents only: a render reports every tile, and each event goes to every listener.
  const int percent = static_cast<int>(done * 100);
  std::lock_guard lock(runner_.mutex_);
  runner_.status_.fraction = done;
  if (percent == percent_) return;
  percent_ = percent;
  runner_.publish("progress", {{"job", runner_.status_.job}, {"stage", name}, {"fraction", percent / 100.0}});
}

void JobRunner::Progress::answered() {
  runner_.check_cancelled();
  std::lock_guard lock(runner_.mutex_);
  runner_.status_.answered = true;
  runner_.publish("answered", {{"job", runner_.status_.job}, {"stage", runner_.status_.stage}});
}

void JobRunner::check_cancelled() const {
  if (cancelled_) throw JobCancelled();
}

bool JobRunner::start(const std::string& name, Job job, WhileRunning running) {
  std::unique_lock lock(mutex_);
  if (stopped_) return false;
  if (status_.state == JobState::Running) {
    // (Without a worker to join, another start is already joining it.)
    if (running != WhileRunning::ReplaceAnswered || !status_.answered || !worker_.joinable()) return false;
    cancelled_ = true, replaced_ = true;  // it ends within its stage's next step, then is joined below
  }
  // The previous job has set its final state, so its thread is ending: join it first.
  if (worker_.joinable()) {
    std::thread finished = std::move(worker_);
    lock.unlock();
    finished.join();
    lock.lock();
    if (stopped_ || status_.state == JobState::Running) return false;
  }
  cancelled_ = false, replaced_ = false;
  status_ = JobStatus{JobState::Running, name, "", 0, 0, 0, "", false};
  publish("state", status_.to_json());
  worker_ = std::thread([this, job = std::move(job)] {
    Progress progress(*this);
    // The stages' loops check the flag too (docs/design.md, Serving: cancelling).
    const CancelScope scope(cancelled_);
    JobState end = JobState::Done;
    std::string error;
    try {
      job(progress);
    } catch (const Cancelled&) {
      std::lock_guard lock(mutex_);
      end = JobState::Cancelled;
      const std::string during = status_.stage.empty() ? std::string() : " during the " + status_.stage + " stage";
      if (replaced_)
        error = "stopped" + during + " after its answer: the next " + status_.job + " replaces its city";
      else if (status_.answered)
        error = "cancelled" + during + " after its answer (POST /api/cancel, or the server stopping); its city stays";
      else
        error = "cancelled" + during +
                " (POST /api/cancel, or the server stopping); the outputs from before stay as they were";
    } catch (const std::exception& e) {
      end = JobState::Failed, error = e.what();
    } catch (...) {
      end = JobState::Failed, error = "an unknown failure";
    }
    std::lock_guard done(mutex_);
    status_.state = end, status_.error = error;
    publish("state", status_.to_json());
  });
  return true;
}

JobStatus JobRunner::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

bool JobRunner::cancel() {
  std::lock_guard lock(mutex_);
  if (status_.state != JobState::Running) return false;
  cancelled_ = true;
  return true;
}

void JobRunner::stop() {
  std::thread worker;
  {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    cancelled_ = true;
    worker = std::move(worker_);
  }
  if (worker.joinable()) worker.join();
  changed_.notify_all();
}

void JobRunner::publish(const std::string& name, nlohmann::json data) {
  events_.push_back({++last_id_, name, std::move(data)});
  if (events_.size() > kKeptEvents) events_.pop_front();
  changed_.notify_all();
}

std::vector<JobEvent> JobRunner::events_after(std::uint64_t after, std::chrono::milliseconds wait) const {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, wait, [&] { return last_id_ > after || stopped_; });
  std::vector<JobEvent> out;
  for (const JobEvent& e : events_)
    if (e.id > after) out.push_back(e);
  return out;
}

std::uint64_t JobRunner::last_event() const {
  std::lock_guard lock(mutex_);
  return last_id_;
}

}  // namespace exacity::serve
