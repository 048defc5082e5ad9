// xvfb_server.cpp - fork/exec Xvfb, read its display number from the -displayfd pipe, RandR requests, kill by PID.
#include "present/xvfb_server.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <xcb/randr.h>

#include <chrono>
#include <cstring>

namespace ht::present {
namespace {

constexpr int kStartTimeoutMs = 10000;

// The display number Xvfb writes to the -displayfd pipe once it accepts connections ("" on timeout or exit).
std::string readDisplayNumber(int fd) {
  std::string text;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kStartTimeoutMs);
  while (text.find('\n') == std::string::npos) {
    auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return "";
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(left)) <= 0) return "";
    char buf[32];
    ssize_t n = read(fd, buf, sizeof buf);
    if (n <= 0) return "";
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text.substr(0, text.find('\n'));
}

void checkRequest(const XConnection& x, xcb_void_cookie_t cookie, const std::string& what) {
  if (xcb_generic_error_t* e = xcb_request_check(x.get(), cookie)) {
    int code = e->error_code;
    std::free(e);
    throw PresentError("Xvfb " + x.name() + ": " + what + " failed (X error " + std::to_string(code) + ")");
  }
  if (!x.alive()) throw PresentError("Xvfb " + x.name() + ": " + what + " closed the connection");
}

}  // namespace

XvfbServer::XvfbServer(std::uint32_t width, std::uint32_t height, const std::string& display) {
  int fds[2];
  if (pipe(fds) != 0) throw PresentError("pipe() for Xvfb failed");
  const std::string screen = std::to_string(width) + "x" + std::to_string(height) + "x24";
  const std::string fd = std::to_string(fds[1]);
  pid_ = fork();
  if (pid_ == 0) {
    close(fds[0]);
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    if (display.empty()) {
      execlp("Xvfb", "Xvfb", "-screen", "0", screen.c_str(), "-noreset", "-nolisten", "tcp", "-displayfd", fd.c_str(),
             static_cast<char*>(nullptr));
    } else {
      execlp("Xvfb", "Xvfb", display.c_str(), "-screen", "0", screen.c_str(), "-noreset", "-nolisten", "tcp",
             "-displayfd", fd.c_str(), static_cast<char*>(nullptr));
    }
    _exit(127);
  }
  close(fds[1]);
  std::string number = pid_ > 0 ? readDisplayNumber(fds[0]) : "";
  close(fds[0]);
  if (number.empty()) {
    kill();
    throw PresentError("Xvfb did not start (is the xvfb package installed?)");
  }
  display_ = ":" + number;
  x_ = std::make_unique<XConnection>(display_);
}

XvfbServer::~XvfbServer() {
  x_.reset();
  kill();
}

void XvfbServer::kill() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
  pid_ = -1;
}

std::uint32_t XvfbServer::outputId(const std::string& name) const {
  auto cookie = xcb_randr_get_screen_resources_current(x_->get(), x_->root());
  XReply<xcb_randr_get_screen_resources_current_reply_t> res(
      xcb_randr_get_screen_resources_current_reply(x_->get(), cookie, nullptr));
  if (!res) throw PresentError("Xvfb: no RandR resources");
  const xcb_randr_output_t* ids = xcb_randr_get_screen_resources_current_outputs(res.get());
  for (int i = 0; i < xcb_randr_get_screen_resources_current_outputs_length(res.get()); ++i) {
    XReply<xcb_randr_get_output_info_reply_t> info(xcb_randr_get_output_info_reply(
        x_->get(), xcb_randr_get_output_info(x_->get(), ids[i], res->config_timestamp), nullptr));
    if (!info) continue;
    std::string n(reinterpret_cast<const char*>(xcb_randr_get_output_info_name(info.get())),
                  static_cast<std::size_t>(xcb_randr_get_output_info_name_length(info.get())));
    if (n == name) return ids[i];
  }
  throw PresentError("Xvfb: no output named " + name);
}

// Through the xrandr program: libxcb 1.15's xcb_randr_set_monitor sends a request the server rejects as too long
// (the connection closes with XCB_CONN_CLOSED_REQ_LEN_EXCEED), while `xrandr --setmonitor` works.
void XvfbServer::setMonitor(const std::string& name, const Rect& rect, const std::vector<std::string>& outputs) {
  std::string outputList;
  for (const std::string& o : outputs) outputList += (outputList.empty() ? "" : ",") + o;
  const std::string geometry = std::to_string(rect.width) + "/" + std::to_string(rect.width / 4) + "x" +
                               std::to_string(rect.height) + "/" + std::to_string(rect.height / 4) + "+" +
                               std::to_string(rect.x) + "+" + std::to_string(rect.y);
  runXrandr({"--setmonitor", name, geometry, outputList.empty() ? "none" : outputList});
}

void XvfbServer::deleteMonitor(const std::string& name) { runXrandr({"--delmonitor", name}); }

void XvfbServer::runXrandr(const std::vector<std::string>& args) const {
  std::vector<std::string> argv = {"xrandr", "--display", display_};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargs;
  for (std::string& a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  pid_t child = fork();
  if (child == 0) {
    int null = open("/dev/null", O_WRONLY);
    if (null >= 0) dup2(null, STDOUT_FILENO);
    execvp("xrandr", cargs.data());
    _exit(127);
  }
  int status = -1;
  if (child > 0) waitpid(child, &status, 0);
  if (child <= 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::string line;
    for (const std::string& a : argv) line += a + " ";
    throw PresentError("Xvfb " + display_ + ": `" + line + "` failed (is x11-xserver-utils installed?)");
  }
}

void XvfbServer::setEdid(const std::string& output, const std::vector<std::uint8_t>& edid) {
  const std::uint32_t id = outputId(output);
  const xcb_atom_t atom = x_->atom("EDID");
  checkRequest(*x_, xcb_randr_configure_output_property_checked(x_->get(), id, atom, 0, 0, 0, nullptr),
               "configure EDID property");
  checkRequest(*x_,
               xcb_randr_change_output_property_checked(x_->get(), id, atom, XCB_ATOM_INTEGER, 8, XCB_PROP_MODE_REPLACE,
                                                        static_cast<std::uint32_t>(edid.size()), edid.data()),
               "set EDID");
}

}  // namespace ht::present
