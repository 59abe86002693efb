#include "process.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

namespace rayq::report {

int run_program(const std::vector<std::string>& argv, bool quiet, const std::string& stdin_text)
{
    int pipe_fds[2] = {-1, -1};
    if (!stdin_text.empty() && pipe(pipe_fds) != 0) throw std::runtime_error("pipe: " + std::string(std::strerror(errno)));
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork: " + std::string(std::strerror(errno)));
    if (pid == 0) {
        if (pipe_fds[0] >= 0) {
            dup2(pipe_fds[0], STDIN_FILENO);
            close(pipe_fds[0]);
            close(pipe_fds[1]);
        }
        if (quiet) {
            const int null = open("/dev/null", O_WRONLY);
            dup2(null, STDOUT_FILENO);
            dup2(null, STDERR_FILENO);
        }
        std::vector<char*> args;
        for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
        args.push_back(nullptr);
        execvp(args[0], args.data());
        std::fprintf(stderr, "rayq-validate: cannot run %s: %s\n", args[0], std::strerror(errno));
        _exit(127);
    }
    if (pipe_fds[0] >= 0) {
        close(pipe_fds[0]);
        const struct sigaction ignore{};
        struct sigaction old{};
        struct sigaction ign = ignore;
        ign.sa_handler = SIG_IGN;
        sigaction(SIGPIPE, &ign, &old);  // a program that stops reading must not kill us
        std::size_t at = 0;
        while (at < stdin_text.size()) {
            const ssize_t n = write(pipe_fds[1], stdin_text.data() + at, stdin_text.size() - at);
            if (n <= 0) break;
            at += static_cast<std::size_t>(n);
        }
        close(pipe_fds[1]);
        sigaction(SIGPIPE, &old, nullptr);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) throw std::runtime_error("waitpid: " + std::string(std::strerror(errno)));
    if (WIFEXITED(status)) return WEXITSTATUS(status);
    return 128 + WTERMSIG(status);
}

std::string tools_binary(const std::string& name)
{
    if (const char* dir = std::getenv("RAYQ_TOOLS_DIR")) return std::string(dir) + "/" + name;
    return std::string(RAYQ_TOOLS_BINARY_DIR) + "/" + name;
}

std::filesystem::path temporary_path(const std::string& suffix)
{
    static std::atomic<unsigned> counter{0};
    return std::filesystem::temp_directory_path() /
           ("rayq-validate-" + std::to_string(getpid()) + "-" + std::to_string(counter++) + "-" + suffix);
}

}  // namespace rayq::report
