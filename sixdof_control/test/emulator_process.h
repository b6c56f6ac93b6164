#pragma once
// The Dynamixel emulator (scripts/dynamixel_emulator) as a child process, driven through its stdin commands.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace sixdof_control::test {

class EmulatorProcess {
 public:
  explicit EmulatorProcess(const std::vector<std::string>& args) {
    int in[2], out[2];
    if (pipe(in) != 0 || pipe(out) != 0) throw std::runtime_error("pipe failed");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(in[0], 0);
      dup2(out[1], 1);
      close(in[1]);
      close(out[0]);
      const std::string path =
          std::string(SIXDOF_EMULATOR_PYTHONPATH) + ":" + (getenv("PYTHONPATH") ? getenv("PYTHONPATH") : "");
      setenv("PYTHONPATH", path.c_str(), 1);
      std::vector<char*> argv{const_cast<char*>(SIXDOF_PYTHON), const_cast<char*>(SIXDOF_EMULATOR)};
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(argv[0], argv.data());
      _exit(127);
    }
    close(in[0]);
    close(out[1]);
    to_ = fdopen(in[1], "w");
    from_ = fdopen(out[0], "r");
    const std::string first = line();
    if (first.rfind("port ", 0) != 0) throw std::runtime_error("emulator did not start: '" + first + "'");
    port_ = first.substr(5);
  }

  ~EmulatorProcess() {
    fclose(to_);  // the emulator ends at the end of its input
    fclose(from_);
    int status = 0;
    for (int i = 0; i < 100 && waitpid(pid_, &status, WNOHANG) == 0; ++i) usleep(20000);
    if (waitpid(pid_, &status, WNOHANG) == 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
  }

  const std::string& port() const { return port_; }

  // Sends a command line; its one-line answer.
  std::string send(const std::string& command) {
    fprintf(to_, "%s\n", command.c_str());
    fflush(to_);
    return line();
  }

 private:
  std::string line() {
    char buffer[512];
    if (!fgets(buffer, sizeof(buffer), from_)) return "";
    std::string s(buffer);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    return s;
  }

  pid_t pid_ = -1;
  FILE* to_ = nullptr;
  FILE* from_ = nullptr;
  std::string port_;
};

}  // namespace sixdof_control::test
