#pragma once
// cpp-httplib's server with its per-connection loop replaced (the loop is a virtual
// member of httplib::Server; request parsing, routing and replies stay the
// library's): the request line and headers must arrive by a deadline and within a
// size (the library resets its read timeout per read and buffers a line of any
// length), a chunked body within a budget the handlers set, and a connection whose
// request was refused before its body was read is closed after the reply.
#include <chrono>
#include <cstddef>
#include <limits>
#include <memory>
#include <string>

namespace httplib {
class Server;
}  // namespace httplib

namespace mdhd::service {

// What the connection loop and the handlers running on its thread share about the
// connection being served (one per pool thread at a time).
struct Connection {
  std::chrono::steady_clock::time_point headDeadline;
  bool inHead = true;         // reading the request line and headers
  std::size_t headBytes = 0;  // of this request's head
  // Raw bytes (chunk framing included) a chunked body may still take.
  std::size_t bodyBudget = std::numeric_limits<std::size_t>::max();
  bool bodyOverflow = false;  // a chunked body went past the budget
  bool close = false;         // a body was left unread: no further request on it
  std::string label;          // the route template of the request, once screened

  void begin(std::chrono::steady_clock::time_point deadline) {
    headDeadline = deadline;
    inHead = true;
    headBytes = 0;
    bodyBudget = std::numeric_limits<std::size_t>::max();
    bodyOverflow = false;
    label.clear();
  }
};

// The connection being served on this thread (a handler's), or null.
Connection* currentConnection();

std::unique_ptr<httplib::Server> makeGuardedServer(std::chrono::milliseconds headTimeout,
                                                   std::size_t maxHeadBytes,
                                                   std::size_t drainBytes);

}  // namespace mdhd::service
