// Runs the hostile-input corpus (cases/*.jsonl, format in README.md) against the built vdg binary.
// Each case gets a fresh folder holding a copy of inputs/ plus the case's own files, folders and
// FIFOs; vdg runs there with the case's arguments, and the test checks
//   - the exit status,
//   - that stderr is exactly the expected message: ONE line (or nothing, when none is expected),
//   - that every file that was in the folder is still there, byte for byte,
//   - that a failing run left nothing new behind.
// A case that never ends is stopped by a watchdog alarm (a safety net, not a timed assertion).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A case that runs longer than this is killed (SIGALRM) and fails as hung.
constexpr unsigned kWatchdogSeconds = 120;

struct Case {
  std::string name;
  std::string source;  // "cases/render.jsonl:12"
  std::string error;   // a malformed case: the test fails with this
  Json spec;
};

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One line of a cases file: checked here, so that a malformed case fails with a clear reason.
std::string checkCase(const Json& j) {
  if (!j.is_object()) return "a case must be a JSON object";
  static const std::set<std::string> kKeys = {"name",   "args",    "exit",  "stderr",    "stdout", "files",
                                              "dirs",   "fifos",   "links", "hardlinks", "limits", "stdout_closed",
                                              "signal", "removed", "env",   "note"};
  for (const auto& item : j.items())
    if (!kKeys.count(item.key())) return "unknown field '" + item.key() + "'";
  if (!j.contains("name") || !j["name"].is_string() ||
      !std::regex_match(j["name"].get<std::string>(), std::regex("[A-Za-z0-9_]+")))
    return "'name' must be letters, digits and underscores";
  if (!j.contains("args") || !j["args"].is_array()) return "'args' must be an array of strings";
  for (const auto& a : j["args"])
    if (!a.is_string()) return "'args' must be an array of strings";
  if (!j.contains("exit") || !j["exit"].is_number_integer()) return "'exit' must be an integer";
  if (!j.contains("stderr") || !j["stderr"].is_string()) return "'stderr' must be a string";
  if (j["stderr"].get<std::string>().find('\n') != std::string::npos) return "'stderr' must be one line";
  for (const char* key : {"links", "hardlinks", "env"})
    if (j.contains(key) && (!j[key].is_object() ||
                            !std::all_of(j[key].begin(), j[key].end(), [](const Json& v) { return v.is_string(); })))
      return std::string("'") + key + "' must be an object of strings";
  if (j.contains("limits") && (!j["limits"].is_object() || j["limits"].size() != 1 || !j["limits"].contains("fsize") ||
                               !j["limits"]["fsize"].is_number_unsigned()))
    return "'limits' must be {\"fsize\": BYTES}";
  if (j.contains("stdout_closed") && !j["stdout_closed"].is_boolean()) return "'stdout_closed' must be true or false";
  if (j.contains("signal")) {
    const Json& s = j["signal"];
    if (!s.is_object() || !s.contains("name") || !s.contains("after") || s.size() != 2 || !s["after"].is_string() ||
        !s["name"].is_string() || !std::set<std::string>{"INT", "TERM", "KILL"}.count(s["name"].get<std::string>()))
      return "'signal' must be {\"name\": \"INT\"|\"TERM\"|\"KILL\", \"after\": REGEX}";
  }
  if (j.contains("removed") && (!j["removed"].is_array() || !std::all_of(j["removed"].begin(), j["removed"].end(),
                                                                         [](const Json& v) { return v.is_string(); })))
    return "'removed' must be an array of strings";
  return {};
}

std::vector<Case> loadCases() {
  std::vector<Case> cases;
  std::set<std::string> names;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(fs::path(VDG_HOSTILE_DIR) / "cases"))
    if (entry.path().extension() == ".jsonl") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::istringstream lines(readAll(file));
    int number = 0;
    for (std::string line; std::getline(lines, line);) {
      ++number;
      if (line.find_first_not_of(" \t") == std::string::npos || line.rfind("//", 0) == 0) continue;
      Case c;
      c.source = "cases/" + file.filename().string() + ":" + std::to_string(number);
      try {
        c.spec = Json::parse(line);
        c.error = checkCase(c.spec);
      } catch (const Json::exception& e) {
        c.error = std::string("not valid JSON: ") + e.what();
      }
      c.name = c.error.empty() ? c.spec["name"].get<std::string>()
                               : "malformed_" + file.stem().string() + "_line" + std::to_string(number);
      if (c.error.empty() && !names.insert(c.name).second) {
        c.error = "duplicate case name '" + c.name + "'";
        c.name += "_duplicate_line" + std::to_string(number);
      }
      for (char& ch : c.name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// A file's content: a string, or an array of parts, each a string or [string, repeat count].
std::string content(const Json& value) {
  if (value.is_string()) return value.get<std::string>();
  std::string out;
  for (const Json& part : value) {
    if (part.is_string()) {
      out += part.get<std::string>();
    } else {
      const std::string piece = part.at(0).get<std::string>();
      for (int i = 0, n = part.at(1).get<int>(); i < n; ++i) out += piece;
    }
  }
  return out;
}

class Folder {
 public:
  Folder() {
    std::random_device rd;
    path_ = fs::temp_directory_path() / ("vdg-hostile-" + std::to_string(rd()) + std::to_string(rd()));
    fs::create_directories(path_);
  }
  ~Folder() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Every entry under `root` by relative path: regular files with their bytes, others marked by kind.
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> out;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const std::string rel = fs::relative(it->path(), root).string();
    const fs::file_status status = it->symlink_status();
    if (fs::is_symlink(status))
      out[rel] = "link:" + fs::read_symlink(it->path()).string();
    else if (fs::is_regular_file(status))
      out[rel] = "file:" + readAll(it->path());
    else if (fs::is_directory(status))
      out[rel] = "<folder>";
    else if (fs::is_fifo(status))
      out[rel] = "<fifo>";
    else
      out[rel] = "<other>";
  }
  return out;
}

struct Outcome {
  int exit = -1;
  std::string signal;  // non-empty when the process died of a signal it was not sent by the case
  std::string out, err;
};

// How a case runs vdg, beyond its arguments.
struct RunSetup {
  std::map<std::string, std::string> env;
  long long fsize = -1;        // RLIMIT_FSIZE in bytes, or -1 for none
  bool stdout_closed = false;  // stdout is a pipe whose reader has already gone
  int signal = 0;              // sent once a path under the folder matches `signal_after`
  std::regex signal_after;
};

int signalNumber(const std::string& name) {
  if (name == "INT") return SIGINT;
  if (name == "TERM") return SIGTERM;
  return SIGKILL;
}

// True once some path under `root` (relative, '/'-separated) matches `pattern`.
bool anyPathMatches(const fs::path& root, const std::regex& pattern) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (std::regex_match(fs::relative(it->path(), root, ec).generic_string(), pattern)) return true;
  return false;
}

// Waits for `pid`; with a case signal, sends it once its path exists. Returns the wait status, or
// -1 when waiting failed.
int waitFor(pid_t pid, const fs::path& cwd, const RunSetup& setup, bool& sent) {
  int status = 0;
  while (setup.signal != 0 && !sent) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (done < 0) return -1;
    if (anyPathMatches(cwd, setup.signal_after)) {
      ::kill(pid, setup.signal);
      sent = true;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  return ::waitpid(pid, &status, 0) == pid ? status : -1;
}

Outcome runVdg(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& scratch,
               const RunSetup& setup) {
  std::vector<std::string> argv_text = {VDG_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    if (!setup.env.count(entry.substr(0, entry.find('=')))) env_text.push_back(entry);
  }
  for (const auto& [key, value] : setup.env) env_text.push_back(key + "=" + value);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  const std::string out_path = (scratch / "stdout").string(), err_path = (scratch / "stderr").string();
  // A pipe with no reader: vdg's first write to stdout meets EPIPE (and SIGPIPE).
  int closed_pipe[2] = {-1, -1};
  if (setup.stdout_closed && (::pipe(closed_pipe) != 0 || ::close(closed_pipe[0]) != 0)) return {-1, "no pipe", {}, {}};

  const pid_t pid = ::fork();
  if (pid == 0) {
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = setup.stdout_closed ? closed_pipe[1] : ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || out < 0 || err < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(126);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    // vdg starts with the dispositions a shell gives it, whatever the test runner ignores.
    for (int sig : {SIGPIPE, SIGXFSZ, SIGINT, SIGTERM}) ::signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    if (setup.fsize >= 0) {
      const rlimit limit{static_cast<rlim_t>(setup.fsize), static_cast<rlim_t>(setup.fsize)};
      if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(126);
    }
    ::alarm(kWatchdogSeconds);  // survives exec: a hung vdg dies of SIGALRM
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  if (setup.stdout_closed) ::close(closed_pipe[1]);
  Outcome o;
  bool sent = false;
  const int status = pid < 0 ? -1 : waitFor(pid, cwd, setup, sent);
  if (status == -1) {
    o.signal = "could not run";
    return o;
  }
  if (WIFEXITED(status)) o.exit = WEXITSTATUS(status);
  if (WIFSIGNALED(status) && sent && setup.signal == SIGKILL && WTERMSIG(status) == SIGKILL)
    o.exit = 128 + SIGKILL;  // the case killed it, as it meant to
  else if (WIFSIGNALED(status))
    o.signal = WTERMSIG(status) == SIGALRM ? "hung (killed by the watchdog)" : strsignal(WTERMSIG(status));
  if (setup.signal != 0 && !sent) o.signal = "it ended before the case's signal could be sent";
  if (!setup.stdout_closed) o.out = readAll(out_path);
  o.err = readAll(err_path);
  return o;
}

// Printed by GoogleTest for a failing case, instead of the object's bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.source; }

class Hostile : public ::testing::TestWithParam<Case> {};

TEST_P(Hostile, GivesItsMessageAndTouchesNothing) {
  const Case& c = GetParam();
  ASSERT_TRUE(c.error.empty()) << c.source << ": " << c.error;
  const Json& j = c.spec;
  Folder folder, scratch;
  const fs::path& dir = folder.path();
  const std::string tmp = dir.string();
  auto expand = [&](const std::string& s) { return replaceAll(s, "{tmp}", tmp); };

  for (const auto& entry : fs::directory_iterator(fs::path(VDG_HOSTILE_DIR) / "inputs"))
    fs::copy(entry.path(), dir / entry.path().filename(), fs::copy_options::recursive);
  const Json dirs = j.value("dirs", Json::array()), fifos = j.value("fifos", Json::array());
  const Json files = j.value("files", Json::object()), env_vars = j.value("env", Json::object());
  for (const Json& d : dirs) fs::create_directories(dir / expand(d.get<std::string>()));
  for (const Json& f : fifos)
    ASSERT_EQ(::mkfifo((dir / expand(f.get<std::string>())).c_str(), 0600), 0) << c.source << ": mkfifo";
  for (const auto& [name, value] : files.items()) {
    const fs::path path = dir / expand(name);
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << content(value);
  }
  const Json links = j.value("links", Json::object()), hardlinks = j.value("hardlinks", Json::object());
  for (const auto& [name, target] : links.items())
    fs::create_symlink(expand(target.get<std::string>()), dir / expand(name));
  for (const auto& [name, existing] : hardlinks.items())
    fs::create_hard_link(dir / expand(existing.get<std::string>()), dir / expand(name));
  RunSetup setup;
  for (const auto& [key, value] : env_vars.items()) setup.env[key] = value.get<std::string>();
  if (j.contains("limits")) setup.fsize = j["limits"]["fsize"].get<long long>();
  setup.stdout_closed = j.value("stdout_closed", false);
  if (j.contains("signal")) {
    setup.signal = signalNumber(j["signal"]["name"].get<std::string>());
    setup.signal_after = std::regex(expand(j["signal"]["after"].get<std::string>()));
  }
  std::set<std::string> removed;
  const Json removed_list = j.value("removed", Json::array());
  for (const Json& r : removed_list) removed.insert(expand(r.get<std::string>()));
  std::vector<std::string> args;
  for (const Json& a : j["args"]) args.push_back(expand(a.get<std::string>()));

  const auto before = snapshot(dir);
  const Outcome o = runVdg(args, dir, scratch.path(), setup);
  const auto after = snapshot(dir);

  SCOPED_TRACE(c.source);
  ASSERT_TRUE(o.signal.empty()) << "vdg did not exit: " << o.signal << "\nstderr: " << o.err;
  const std::string expected = expand(j["stderr"].get<std::string>());
  EXPECT_EQ(o.err, expected.empty() ? "" : expected + "\n");
  EXPECT_LE(std::count(o.err.begin(), o.err.end(), '\n'), 1) << "the message must be one line";
  EXPECT_EQ(o.exit, j["exit"].get<int>()) << "stderr: " << o.err;
  if (j.contains("stdout")) {
    EXPECT_EQ(o.out, expand(j["stdout"].get<std::string>()));
  }
  for (const std::string& rel : removed) EXPECT_FALSE(after.count(rel)) << rel << " should have been removed";
  for (const auto& [rel, was] : before) {
    if (removed.count(rel)) continue;
    const auto now = after.find(rel);
    EXPECT_TRUE(now != after.end() && now->second == was) << rel << " was changed or removed";
  }
  if (o.exit != 0) {
    // A run killed by SIGKILL cannot remove the temp file it was writing; the next run does.
    const bool killed = setup.signal == SIGKILL;
    for (const auto& [rel, what] : after)
      EXPECT_TRUE(before.count(rel) || (killed && fs::path(rel).filename().string().rfind(".vdg-", 0) == 0))
          << "a failing run left " << rel << " behind";
  }
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Corpus, Hostile, ::testing::ValuesIn(loadCases()), caseName);

}  // namespace
