#include "app/commands/Gnuplot.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>

#include "util/Error.h"

extern char** environ;

namespace candela {

namespace {

/// Closes the descriptors it holds (a pipe's ends) on every path out.
struct Fds {
    int fd[6] = {-1, -1, -1, -1, -1, -1};
    ~Fds() {
        for (int& f : fd) closeOne(f);
    }
    static void closeOne(int& f) {
        if (f >= 0) ::close(f);
        f = -1;
    }
};

/// The last lines of gnuplot's messages, enough to say what went wrong on one screen.
std::string tail(const std::string& text) {
    constexpr size_t kMaxChars = 600;
    std::string t = text.size() > kMaxChars ? "..." + text.substr(text.size() - kMaxChars) : text;
    while (!t.empty() && (t.back() == '\n' || t.back() == ' ')) t.pop_back();
    return t;
}

}  // namespace

bool gnuplotAvailable() {
    return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}

std::string gnuplotOutput(const std::string& script, const std::string& workingDir,
                          const std::string& what) {
    // fd[0], fd[1]: stdin's pipe; fd[2], fd[3]: stdout's; fd[4], fd[5]: stderr's.
    Fds p;
    for (int k = 0; k < 3; ++k)
        if (::pipe2(&p.fd[2 * k], O_CLOEXEC) != 0)
            throw RuntimeError(what + ": cannot run gnuplot (pipe: " + std::strerror(errno) + ")");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, p.fd[0], 0);
    posix_spawn_file_actions_adddup2(&actions, p.fd[3], 1);
    posix_spawn_file_actions_adddup2(&actions, p.fd[5], 2);
    if (!workingDir.empty()) posix_spawn_file_actions_addchdir_np(&actions, workingDir.c_str());
    char arg0[] = "gnuplot";
    char* argv[] = {arg0, nullptr};
    pid_t pid = 0;
    int spawned = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
        throw RuntimeError(what + ": cannot run gnuplot (" + std::strerror(spawned) + ")");
    Fds::closeOne(p.fd[0]);
    Fds::closeOne(p.fd[3]);
    Fds::closeOne(p.fd[5]);
    for (int k : {1, 2, 4}) ::fcntl(p.fd[k], F_SETFL, ::fcntl(p.fd[k], F_GETFL) | O_NONBLOCK);

    // A gnuplot that exits before reading all of the script makes the write fail with EPIPE
    // instead of raising SIGPIPE: the signal is blocked in this thread and any pending one
    // consumed before restoring the mask.
    sigset_t pipeSignal, previousMask;
    sigemptyset(&pipeSignal);
    sigaddset(&pipeSignal, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipeSignal, &previousMask);

    std::string out, err;
    size_t written = 0;
    if (script.empty()) Fds::closeOne(p.fd[1]);
    while (p.fd[1] >= 0 || p.fd[2] >= 0 || p.fd[4] >= 0) {
        pollfd fds[3] = {{p.fd[1], POLLOUT, 0}, {p.fd[2], POLLIN, 0}, {p.fd[4], POLLIN, 0}};
        if (::poll(fds, 3, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (p.fd[1] >= 0 && fds[0].revents) {
            ssize_t n = ::write(p.fd[1], script.data() + written, script.size() - written);
            if (n > 0) written += size_t(n);
            if ((n < 0 && errno != EAGAIN && errno != EINTR) || written == script.size())
                Fds::closeOne(p.fd[1]);
        }
        for (int k : {1, 2}) {
            int& fd = p.fd[2 * k];
            if (fd < 0 || !fds[k].revents) continue;
            char buffer[65536];
            ssize_t n = ::read(fd, buffer, sizeof buffer);
            if (n > 0)
                (k == 1 ? out : err).append(buffer, size_t(n));
            else if (n == 0 || (errno != EAGAIN && errno != EINTR))
                Fds::closeOne(fd);
        }
    }
    timespec noWait{0, 0};
    while (sigtimedwait(&pipeSignal, nullptr, &noWait) > 0) {
    }
    pthread_sigmask(SIG_SETMASK, &previousMask, nullptr);

    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || out.empty())
        throw RuntimeError(what + ": gnuplot failed" +
                           (err.empty() ? std::string() : ": " + tail(err)));
    return out;
}

}  // namespace candela
