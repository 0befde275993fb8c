// The server's worker: one generation or render at a time, off the threads that answer
// requests, its stages told as events and cancellable (docs/design.md, Serving).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "generate/cancel.h"

namespace exacity::serve {

enum class JobState { Idle, Running, Done, Failed, Cancelled };

struct JobStatus {
  JobState state = JobState::Idle;
  std::string job;           // "generate" or "render"; empty while idle
  std::string stage;         // the stage under way, or the last one
  int index = 0, count = 0;  // the stage's position (1-based) and the stage count, as the CLI prints them
  double fraction = 0;       // within a long stage (rendering)
  std::string error;         // for Failed and Cancelled: the one-line message
  // The job has answered: what the page shows is written, and what it goes on with
  // (a generation's validation) is not awaited by the page (Progress::answered).
  bool answered = false;
  nlohmann::json to_json() const;
};

// One thing that happened, for GET /api/events: "stage", "progress", "answered" or "state".
struct JobEvent {
  std::uint64_t id = 0;
  std::string name;
  nlohmann::json data;
};

// Thrown inside a job at its next progress report, or inside a stage's loop, once it is
// cancelled (generate/cancel.h).
using JobCancelled = Cancelled;

class JobRunner {
 public:
  // What a job reports through; each call throws JobCancelled once the job is cancelled.
  class Progress {
   public:
    void stage(int index, int count, const std::string& name);
    void fraction(const std::string& name, double done);
    // What the page shows is there: an "answered" event, and the status says so until the
    // job ends. The job goes on with what the page does not wait for.
    void answered();

   private:
    friend class JobRunner;
    explicit Progress(JobRunner& runner) : runner_(runner) {}
    JobRunner& runner_;
    int percent_ = -1;
  };
  using Job = std::function<void(Progress&)>;

  JobRunner() = default;
  ~JobRunner() { stop(); }
  JobRunner(const JobRunner&) = delete;
  JobRunner& operator=(const JobRunner&) = delete;

  // What start does while a job runs: refuse, or, when the running job has answered,
  // cancel what it goes on with, wait for it to end and start (a generation after an edit
  // does not wait for the last one's validation, whose city it replaces).
  enum class WhileRunning { Refuse, ReplaceAnswered };
  // Starts `job` on the worker; false while another runs (as `running` says) or after
  // stop(). A job that throws fails with the exception's message; one cancelled ends Cancelled.
  bool start(const std::string& name, Job job, WhileRunning running = WhileRunning::Refuse);
  JobStatus status() const;
  // The running job stops within its stage: at its next progress report or its stage's next
  // loop step (generate/cancel.h). False when no job runs.
  bool cancel();
  // Cancels the running job, waits for it, and starts no more.
  void stop();

  // The events after `after`, waiting up to `wait` for one; the id of the last event so far.
  std::vector<JobEvent> events_after(std::uint64_t after, std::chrono::milliseconds wait) const;
  std::uint64_t last_event() const;

 private:
  void publish(const std::string& name, nlohmann::json data);  // with mutex_ held
  void check_cancelled() const;

  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::thread worker_;
  std::atomic<bool> cancelled_{false};
  bool replaced_ = false;  // cancelled after its answer by the next job's start
  bool stopped_ = false;
  JobStatus status_;
  std::deque<JobEvent> events_;  // the most recent kKeptEvents
  std::uint64_t last_id_ = 0;
  static constexpr std::size_t kKeptEvents = 256;
};

const char* state_name(JobState state);

}  // namespace exacity::serve
