// httplib's server with its connections kept in hand (docs/design.md, Serving: connections):
// a request must arrive within a deadline, however slowly it trickles in; a client address
// holds a bounded number of connections; and when every request thread is taken, the
// connection waiting longest for its request gives its thread up, so slow or idle clients
// never keep the API from answering.
#pragma once

#include <httplib.h>

#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace exacity::serve {

struct ConnectionLimits {
  std::size_t threads = 32;     // request threads
  std::size_t per_client = 24;  // connections from one address: its 16 event streams and more
  // From a request's first byte to its headers' end, and from there to its body's end.
  std::chrono::milliseconds headers{10000}, body{60000};
};

// The connections being served, each waiting for its request (idle, or the request still
// arriving) or being answered.
class ConnectionTable {
 public:
  explicit ConnectionTable(std::size_t per_client) : per_client_(per_client) {}
  // Takes in a connection from `client`. Past the client's cap its connection waiting
  // longest is closed, or, when all of them are being answered, false: the new one is not
  // taken.
  bool open(socket_t sock, const std::string& client);
  void waiting(socket_t sock);    // for its (next) request
  void answering(socket_t sock);  // its request is in
  // Before the socket is closed.
  void close(socket_t sock);
  // Shuts down the connection waiting longest, of the client holding the most connections;
  // false when every connection is being answered.
  bool drop_one();
  // Shuts every connection down (a stopping server's).
  void drop_all();

 private:
  struct Entry {
    std::string client;
    bool answering = false, dropped = false;
    std::chrono::steady_clock::time_point since;
  };
  bool drop_waiting(const std::string* client);  // with mutex_ held
  std::mutex mutex_;
  std::map<socket_t, Entry> open_;
  std::map<std::string, std::size_t> per_address_;
  std::size_t per_client_;
};

class HttpServer : public httplib::Server {
 public:
  explicit HttpServer(ConnectionLimits limits);
  // Closes every connection; after stop(), so that none is held open.
  void drop_connections() { table_->drop_all(); }

 private:
  bool process_and_close_socket(socket_t sock) override;
  ConnectionLimits limits_;
  std::shared_ptr<ConnectionTable> table_;
};

}  // namespace exacity::serve
