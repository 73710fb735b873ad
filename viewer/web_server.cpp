#include "viewer/web_server.hpp"

#include <chrono>
#include <deque>
#include <optional>
#include <stdexcept>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <nlohmann/json.hpp>

namespace tongue::viewer {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
using Request = http::request<http::string_body>;

constexpr std::size_t kMaxConnections = 64;       // HTTP and WebSocket together
constexpr auto kIdle = std::chrono::seconds(30);  // an HTTP request must arrive within this
constexpr std::size_t kMaxHeader = 8192;          // bytes of a request's header
constexpr std::size_t kMaxBody = 1024;            // bytes of a request's body (GETs have none)
constexpr std::size_t kMaxPageMessage = 4096;  // bytes of a message from a page ({"type":"next"})
constexpr std::size_t kMaxQueued = 64;  // messages waiting for a page that does not read: cut off

// Connections open now, shared by the listener and every connection it made.
using OpenCount = std::shared_ptr<std::size_t>;

class Counted {
 public:
  explicit Counted(OpenCount count) : count_(std::move(count)) { ++*count_; }
  ~Counted() { --*count_; }
  Counted(const Counted&) = delete;
  Counted& operator=(const Counted&) = delete;

 private:
  OpenCount count_;
};

// One page's WebSocket: sends what the hub gives it, in order, one write at a time; reads the
// page's "next" requests.
class WsPage : public Page, public std::enable_shared_from_this<WsPage> {
 public:
  WsPage(tcp::socket&& socket, LiveHub& hub, OpenCount count)
      : ws_(std::move(socket)), hub_(hub), counted_(std::move(count)) {}

  void start(Request request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(kMaxPageMessage);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code ec) {
      if (ec) return;
      self->hub_.join(self);
      self->read();
    });
  }

  void send(std::shared_ptr<const std::string> text) override {
    if (gone_) return;
    if (queue_.size() >= kMaxQueued) return close();
    queue_.push_back(std::move(text));
    if (!writing_) write();
  }

 private:
  void read() {
    ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->leave();
      const std::string text = beast::buffers_to_string(self->buffer_.data());
      self->buffer_.consume(self->buffer_.size());
      // Anything but {"type": "next"} is ignored: a page has nothing else to say.
      const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
      if (j.is_object()) {
        const auto type = j.find("type");
        if (type != j.end() && type->is_string() && *type == "next")
          self->hub_.want_frame(self.get());
      }
      self->read();
    });
  }

  void write() {
    writing_ = true;
    ws_.text(true);
    ws_.async_write(net::buffer(*queue_.front()),
                    [self = shared_from_this()](beast::error_code ec, std::size_t) {
                      self->queue_.pop_front();
                      if (ec) return self->leave();
                      if (self->queue_.empty()) {
                        self->writing_ = false;
                      } else {
                        self->write();
                      }
                    });
  }

  void leave() {
    if (gone_) return;
    gone_ = true;
    hub_.leave(this);
  }

  void close() {
    leave();
    beast::error_code ignored;
    beast::get_lowest_layer(ws_).socket().close(ignored);
  }

  websocket::stream<beast::tcp_stream> ws_;
  LiveHub& hub_;
  Counted counted_;
  beast::flat_buffer buffer_;
  std::deque<std::shared_ptr<const std::string>> queue_;
  bool writing_ = false;
  bool gone_ = false;
};

// One HTTP connection: requests answered in turn, until the client closes it or stays idle.
class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket&& socket, const Routes& routes, LiveHub* hub, OpenCount count)
      : stream_(std::move(socket)), routes_(routes), hub_(hub), count_(count), counted_(count) {}

  void read() {
    parser_.emplace();
    parser_->header_limit(kMaxHeader);
    parser_->body_limit(kMaxBody);
    stream_.expires_after(kIdle);
    http::async_read(stream_, buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code ec, std::size_t) {
                       if (ec) return self->close();
                       self->handle(self->parser_->release());
                     });
  }

 private:
  void handle(Request request) {
    if (websocket::is_upgrade(request)) {
      if (hub_ && request.target() == "/ws") {
        stream_.expires_never();
        std::make_shared<WsPage>(stream_.release_socket(), *hub_, count_)
            ->start(std::move(request));
        return;
      }
      return reply(request, {404, "text/plain", "no WebSocket here (a replay has none)"});
    }
    if (request.method() != http::verb::get && request.method() != http::verb::head)
      return reply(request, {405, "text/plain", "only GET and HEAD"});
    const beast::string_view target = request.target();
    reply(request, routes_.answer(std::string_view(target.data(), target.size())));
  }

  void reply(const Request& request, HttpAnswer answer) {
    auto response = std::make_shared<http::response<http::string_body>>(
        static_cast<http::status>(answer.status), request.version());
    response->set(http::field::server, "tongue_viewer");
    response->set(http::field::content_type, answer.content_type);
    response->set(http::field::cache_control, "no-store");
    response->set("X-Content-Type-Options", "nosniff");
    response->keep_alive(request.keep_alive());
    if (request.method() == http::verb::head) {
      response->content_length(answer.body.size());
    } else {
      response->body() = std::move(answer.body);
      response->prepare_payload();
    }
    http::async_write(stream_, *response,
                      [self = shared_from_this(), response](beast::error_code ec, std::size_t) {
                        if (ec || !response->keep_alive()) return self->close();
                        self->read();
                      });
  }

  void close() {
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
  }

  beast::tcp_stream stream_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  const Routes& routes_;
  LiveHub* hub_;
  OpenCount count_;
  Counted counted_;
};

}  // namespace

struct WebServer::Impl : std::enable_shared_from_this<WebServer::Impl> {
  Impl(net::io_context& io, const Routes& routes, LiveHub* hub)
      : io(io), acceptor(io), routes(routes), hub(hub) {}

  void accept() {
    acceptor.async_accept(
        io, [self = shared_from_this()](beast::error_code ec, tcp::socket socket) {
          if (ec == net::error::operation_aborted) return;
          if (!ec) {
            if (*self->open >= kMaxConnections) {
              socket.close(ec);  // too many: refused, the others go on
            } else {
              std::make_shared<HttpSession>(std::move(socket), self->routes, self->hub, self->open)
                  ->read();
            }
          }
          self->accept();
        });
  }

  net::io_context& io;
  tcp::acceptor acceptor;
  const Routes& routes;
  LiveHub* hub;
  OpenCount open = std::make_shared<std::size_t>(0);
};

WebServer::WebServer(net::io_context& io, const std::string& address, unsigned short port,
                     const Routes& routes, LiveHub* hub)
    : impl_(std::make_shared<Impl>(io, routes, hub)) {
  const std::string where = address + ":" + std::to_string(port);
  beast::error_code ec;
  tcp::resolver resolver(io);
  const auto endpoints = resolver.resolve(address, std::to_string(port), ec);
  if (ec || endpoints.empty())
    throw std::runtime_error(where + ": cannot resolve the address: " + ec.message());
  const tcp::endpoint endpoint = endpoints.begin()->endpoint();
  tcp::acceptor& a = impl_->acceptor;
  a.open(endpoint.protocol(), ec);
  if (!ec) a.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) a.bind(endpoint, ec);
  if (!ec) a.listen(net::socket_base::max_listen_connections, ec);
  if (ec) throw std::runtime_error(where + ": cannot listen: " + ec.message());
}

WebServer::~WebServer() {
  beast::error_code ignored;
  impl_->acceptor.close(ignored);
}

unsigned short WebServer::port() const {
  return impl_->acceptor.local_endpoint().port();
}

void WebServer::start() {
  impl_->accept();
}

}  // namespace tongue::viewer
