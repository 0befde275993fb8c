#include "serve/connections.h"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <thread>
#include <vector>

namespace exacity::serve {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

std::string address_of(const sockaddr_storage& address, socklen_t length, int* port) {
  char host[NI_MAXHOST] = "", service[NI_MAXSERV] = "";
  if (getnameinfo(reinterpret_cast<const sockaddr*>(&address), length, host, sizeof host, service, sizeof service,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return "";
  if (port) *port = std::atoi(service);
  return host;
}

std::string peer_address(socket_t sock, int* port = nullptr) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (getpeername(sock, reinterpret_cast<sockaddr*>(&address), &length) != 0) return "";
  return address_of(address, length, port);
}

std::string local_address(socket_t sock, int* port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (getsockname(sock, reinterpret_cast<sockaddr*>(&address), &length) != 0) return "";
  return address_of(address, length, port);
}

// poll() for `events`, at most `wait`; whether they came.
bool ready(socket_t sock, short events, milliseconds wait) {
  pollfd p{sock, events, 0};
  int n;
  do {
    n = poll(&p, 1, static_cast<int>(std::max<milliseconds::rep>(0, wait.count())));
  } while (n < 0 && errno == EINTR);
  return n > 0;
}

// One request read from a connection and its answer written, as httplib's SocketStream
// does, but the request must be in by its deadlines however slowly it trickles in (a
// read timeout alone restarts with every byte); past them nothing is read or written.
class RequestStream : public httplib::Stream {
 public:
  RequestStream(socket_t sock, ConnectionTable& table, const ConnectionLimits& limits, milliseconds read_timeout,
                milliseconds write_timeout)
      : sock_(sock),
        table_(table),
        limits_(limits),
        read_timeout_(read_timeout),
        write_timeout_(write_timeout),
        deadline_(Clock::now() + limits.headers) {}

  // The headers are in (httplib's setup_request): the body, if any, has its own deadline.
  void headers_read(const httplib::Request& req) {
    headers_done_ = true;
    chunked_ = req.get_header_value("Transfer-Encoding").find("chunked") != std::string::npos;
    const std::string length = req.get_header_value("Content-Length");
    body_left_ = length.empty() ? 0 : std::strtoull(length.c_str(), nullptr, 10);
    deadline_ = Clock::now() + limits_.body;
    if (body_left_ == 0 && !chunked_) answer();
  }
  // Whether the request was read to its end, so the connection may carry the next one
  // (not when it was refused before its body was read).
  bool read_whole() const { return headers_done_ && !chunked_ && body_left_ == 0 && !late_; }

  bool is_readable() const override {
    milliseconds wait = read_timeout_;
    if (!answering_) {
      const auto left = std::chrono::duration_cast<milliseconds>(deadline_ - Clock::now());
      if (left.count() <= 0) return late_ = true, false;
      wait = std::min(wait, left);
    }
    return ready(sock_, POLLIN, wait);
  }
  bool is_writable() const override {
    if (late_ || !ready(sock_, POLLOUT, write_timeout_)) return false;
    // Still open at the other end (httplib's is_socket_alive): nothing to read, or data.
    if (!ready(sock_, POLLIN, milliseconds(0))) return true;
    char byte;
    return recv(sock_, &byte, 1, MSG_PEEK | MSG_DONTWAIT) > 0;
  }
  ssize_t read(char* ptr, std::size_t size) override {
    if (buffered_ == filled_) {
      if (!is_readable()) return -1;
      if (size >= sizeof buffer_) {
        const ssize_t n = recv(sock_, ptr, size, 0);
        if (n > 0) counted(static_cast<std::size_t>(n));
        return n;
      }
      const ssize_t n = recv(sock_, buffer_, sizeof buffer_, 0);
      if (n <= 0) return n;
      buffered_ = 0, filled_ = static_cast<std::size_t>(n);
    }
    const std::size_t n = std::min(size, filled_ - buffered_);
    std::memcpy(ptr, buffer_ + buffered_, n);
    buffered_ += n;
    counted(n);
    return static_cast<ssize_t>(n);
  }
  ssize_t write(const char* ptr, std::size_t size) override {
    answer();
    if (!is_writable()) return -1;
    return send(sock_, ptr, size, MSG_NOSIGNAL);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override { ip = peer_address(sock_, &port); }
  void get_local_ip_and_port(std::string& ip, int& port) const override { ip = local_address(sock_, &port); }
  socket_t socket() const override { return sock_; }

 private:
  // Bytes httplib took: past the headers, the body's.
  void counted(std::size_t n) {
    if (!headers_done_ || chunked_ || answering_) return;
    body_left_ -= std::min<std::uint64_t>(n, body_left_);
    if (body_left_ == 0) answer();
  }
  void answer() {
    if (answering_) return;
    answering_ = true;
    table_.answering(sock_);
  }

  socket_t sock_;
  ConnectionTable& table_;
  const ConnectionLimits& limits_;
  milliseconds read_timeout_, write_timeout_;
  Clock::time_point deadline_;
  bool headers_done_ = false, chunked_ = false, answering_ = false;
  mutable bool late_ = false;
  std::uint64_t body_left_ = 0;
  char buffer_[4096];
  std::size_t buffered_ = 0, filled_ = 0;  // the buffer's bytes handed out, and held
};

// httplib's thread pool, but a connection arriving when every thread is taken has the
// connection waiting longest for its request closed, so that a thread comes free.
class RequestThreads : public httplib::TaskQueue {
 public:
  RequestThreads(std::size_t n, std::shared_ptr<ConnectionTable> table) : table_(std::move(table)) {
    for (std::size_t i = 0; i < n; ++i) threads_.emplace_back([this] { work(); });
  }
  void enqueue(std::function<void()> fn) override {
    bool taken;
    {
      std::lock_guard lock(mutex_);
      jobs_.push_back(std::move(fn));
      taken = busy_ + jobs_.size() > threads_.size();
    }
    wake_.notify_one();
    if (taken) table_->drop_one();
  }
  void shutdown() override {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

 private:
  void work() {
    for (;;) {
      std::function<void()> job;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return !jobs_.empty() || stopping_; });
        if (jobs_.empty()) return;
        job = std::move(jobs_.front());
        jobs_.pop_front();
        ++busy_;
      }
      job();
      std::lock_guard lock(mutex_);
      --busy_;
    }
  }

  std::shared_ptr<ConnectionTable> table_;
  std::vector<std::thread> threads_;
  std::deque<std::function<void()>> jobs_;
  std::size_t busy_ = 0;
  bool stopping_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace

bool ConnectionTable::open(socket_t sock, const std::string& client) {
  std::lock_guard lock(mutex_);
  if (per_address_[client] >= per_client_ && !drop_waiting(&client)) return false;
  open_[sock] = Entry{client, false, false, Clock::now()};
  ++per_address_[client];
  return true;
}

void ConnectionTable::waiting(socket_t sock) {
  std::lock_guard lock(mutex_);
  Entry& e = open_.at(sock);
  e.answering = false, e.since = Clock::now();
}

void ConnectionTable::answering(socket_t sock) {
  std::lock_guard lock(mutex_);
  open_.at(sock).answering = true;
}

void ConnectionTable::close(socket_t sock) {
  std::lock_guard lock(mutex_);
  const auto at = open_.find(sock);
  if (at == open_.end()) return;
  if (--per_address_[at->second.client] == 0) per_address_.erase(at->second.client);
  open_.erase(at);
}

bool ConnectionTable::drop_one() {
  std::lock_guard lock(mutex_);
  return drop_waiting(nullptr);
}

bool ConnectionTable::drop_waiting(const std::string* client) {
  auto longest = open_.end();
  for (auto it = open_.begin(); it != open_.end(); ++it)
    if (!it->second.answering && !it->second.dropped && (!client || it->second.client == *client) &&
        (longest == open_.end() || it->second.since < longest->second.since))
      longest = it;
  if (longest == open_.end()) return false;
  // Its thread sees the end of the connection and closes it (close() first, under this
  // mutex, so the socket shut here is never one reused since).
  ::shutdown(longest->first, SHUT_RDWR);
  longest->second.dropped = true;
  return true;
}

void ConnectionTable::drop_all() {
  std::lock_guard lock(mutex_);
  for (auto& [sock, entry] : open_) ::shutdown(sock, SHUT_RDWR), entry.dropped = true;
}

HttpServer::HttpServer(ConnectionLimits limits)
    : limits_(limits), table_(std::make_shared<ConnectionTable>(limits.per_client)) {
  new_task_queue = [this] { return new RequestThreads(limits_.threads, table_); };
}

bool HttpServer::process_and_close_socket(socket_t sock) {
  bool ok = false;
  if (table_->open(sock, peer_address(sock))) {
    const auto read_timeout = milliseconds(read_timeout_sec_ * 1000 + read_timeout_usec_ / 1000);
    const auto write_timeout = milliseconds(write_timeout_sec_ * 1000 + write_timeout_usec_ / 1000);
    for (std::size_t left = keep_alive_max_count_; left > 0; --left) {
      table_->waiting(sock);
      // The next request's first byte, for the keep-alive time at most; a stopping server
      // waits for none.
      const auto idle_until = Clock::now() + std::chrono::seconds(keep_alive_timeout_sec_);
      bool arrived = false;
      while (!arrived && svr_sock_ != INVALID_SOCKET && Clock::now() < idle_until)
        arrived = ready(sock, POLLIN, milliseconds(100));
      if (!arrived) break;
      RequestStream stream(sock, *table_, limits_, read_timeout, write_timeout);
      bool closed = false;
      ok = process_request(stream, left == 1, closed, [&](httplib::Request& req) { stream.headers_read(req); });
      if (!ok || closed || !stream.read_whole()) break;
    }
    table_->close(sock);
  }
  ::shutdown(sock, SHUT_RDWR);
  ::close(sock);
  return ok;
}

}  // namespace exacity::serve
