#include "shard/driver/worker_process.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>

extern char** environ;

namespace shard::driver {
namespace {

// A file descriptor closed when it goes out of scope.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  void reset(int fd = -1) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
  }

 private:
  int fd_;
};

std::string errno_text(int error) { return std::strerror(error); }

// Both ends close on exec, so a worker started by another thread at the same moment does not
// inherit them (it would hold this worker's input open and this worker would never see its end).
void make_pipe(Fd& read_end, Fd& write_end) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(fmt::format("cannot create a pipe to a worker process: {}", errno_text(errno)));
  read_end.reset(fds[0]);
  write_end.reset(fds[1]);
}

class SpawnSetup {
 public:
  SpawnSetup() {
    posix_spawn_file_actions_init(&actions);
    posix_spawnattr_init(&attributes);
  }
  ~SpawnSetup() {
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
  }
  SpawnSetup(const SpawnSetup&) = delete;
  SpawnSetup& operator=(const SpawnSetup&) = delete;
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attributes;
};

// Writes all of `data` to `fd`; false when the reader has gone (the worker died before reading).
// SIGPIPE is blocked on this thread meanwhile, and one it raised is taken back, so a dead worker
// shows as EPIPE here and as its exit status below, never as a SIGPIPE that ends the caller.
bool write_all(int fd, const std::string& data) {
  sigset_t pipe_signal, previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  bool complete = true;
  std::size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      complete = false;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  sigset_t pending;
  sigpending(&pending);
  if (sigismember(&pending, SIGPIPE) == 1) {
    const timespec now{0, 0};
    sigtimedwait(&pipe_signal, nullptr, &now);
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  return complete;
}

std::string read_all(int fd) {
  std::string out;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(fmt::format("cannot read a worker process's result: {}", errno_text(errno)));
    if (n == 0) return out;
    out.append(buffer, static_cast<std::size_t>(n));
  }
}

}  // namespace

std::string describe_signal(int signal) {
  const char* abbreviation = sigabbrev_np(signal);
  const char* description = sigdescr_np(signal);
  if (!abbreviation) return fmt::format("signal {}", signal);
  return fmt::format("SIG{} ({})", abbreviation, description ? description : "no description");
}

std::string run_worker_process(const WorkerCommand& command, const std::string& input) {
  Fd input_read, input_write, output_read, output_write;
  make_pipe(input_read, input_write);
  make_pipe(output_read, output_write);

  SpawnSetup setup;
  posix_spawn_file_actions_adddup2(&setup.actions, input_read.get(), STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&setup.actions, output_write.get(), STDOUT_FILENO);
  // The worker starts with no signal blocked and SIGPIPE at its default, whatever this thread has.
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigmask(&setup.attributes, &none);
  posix_spawnattr_setsigdefault(&setup.attributes, &defaults);
  posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);

  const std::string program = command.executable.string();
  std::vector<std::string> words{program};
  words.insert(words.end(), command.arguments.begin(), command.arguments.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  if (const int error = posix_spawn(&pid, program.c_str(), &setup.actions, &setup.attributes, argv.data(), environ);
      error != 0)
    throw std::runtime_error(fmt::format("cannot start the worker process {}: {}", program, errno_text(error)));
  input_read.reset();
  output_write.reset();

  // The worker reads all its input before it writes, so writing first cannot deadlock.
  write_all(input_write.get(), input);
  input_write.reset();
  std::string output;
  std::string read_error;
  try {
    output = read_all(output_read.get());
  } catch (const std::exception& e) {
    read_error = e.what();
  }
  output_read.reset();

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error(fmt::format("cannot wait for the worker process {}: {}", pid, errno_text(errno)));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    throw WorkerDied(fmt::format("the worker process was killed by {}", describe_signal(signal)), signal, -1);
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (code != 0)
    throw WorkerDied(fmt::format("the worker process exited with status {} (its message, if any, is on the standard error above)", code),
                     0, code);
  if (!read_error.empty()) throw std::runtime_error(read_error);
  return output;
}

}  // namespace shard::driver
