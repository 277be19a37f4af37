// A small mutation fuzzer for gcc builds (`make test`): replays the seed corpus, then feeds mutated seeds
// (bit flips, byte edits, cuts, duplicated and spliced ranges, dictionary tokens) through the same entry
// point as the libFuzzer target, until an iteration count or a time budget runs out.
// Usage: fuzz_<reader>_replay SEED_DIR [ITERATIONS] [SECONDS] [RANDOM_SEED] [-dict=FILE]
// The dictionary is libFuzzer's format (one "token" per line, \xNN escapes), shared with `make fuzz`.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

// A hang is a finding too (as libFuzzer's -timeout): an input that runs longer than kInputTimeoutS is
// written to fuzz-timeout-<pid>.bin in the working folder and the run aborts.
constexpr unsigned kInputTimeoutS = 10;
const std::string* g_current_input = nullptr;

extern "C" void on_input_timeout(int) {
  char name[64];
  const int length = std::snprintf(name, sizeof name, "fuzz-timeout-%d.bin", static_cast<int>(getpid()));
  const int fd = open(name, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0 && g_current_input) {
    const ssize_t written = write(fd, g_current_input->data(), g_current_input->size());
    (void)written;
    close(fd);
  }
  const char message[] = "fuzz replay: an input ran longer than the timeout; it is in ";
  ssize_t ignored = write(2, message, sizeof message - 1);
  ignored = write(2, name, static_cast<std::size_t>(length));
  ignored = write(2, "\n", 1);
  (void)ignored;
  _exit(3);
}

int run(const std::string& bytes) {
  g_current_input = &bytes;
  alarm(kInputTimeoutS);
  const int result =
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  alarm(0);
  return result;
}

std::string mutate(std::string s, const std::vector<std::string>& corpus,
                   const std::vector<std::string>& tokens, std::mt19937_64& rng) {
  auto pos = [&](std::size_t n) {
    return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % (n + 1));
  };
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    switch (rng() % 8) {
      case 0:
        if (!s.empty()) s[pos(s.size() - 1)] ^= static_cast<char>(1u << (rng() % 8));
        break;
      case 1:
        if (!s.empty()) s[pos(s.size() - 1)] = static_cast<char>(rng() % 256);
        break;
      case 2:
        s.insert(pos(s.size()), 1, static_cast<char>(rng() % 256));
        break;
      case 3: {
        const std::size_t at = pos(s.size());
        s.erase(at, pos(std::min<std::size_t>(64, s.size() - at)));
        break;
      }
      case 4:
        s.resize(pos(s.size()));
        break;
      case 5: {
        const std::size_t at = pos(s.size());
        const std::size_t len = pos(std::min<std::size_t>(256, s.size() - at));
        s.insert(pos(s.size()), s.substr(at, len));
        break;
      }
      case 6: {
        const std::string& other = corpus[rng() % corpus.size()];
        const std::size_t at = pos(other.size());
        s.insert(pos(s.size()), other.substr(at, pos(std::min<std::size_t>(512, other.size() - at))));
        break;
      }
      default:
        if (!tokens.empty()) s.insert(pos(s.size()), tokens[rng() % tokens.size()]);
        break;
    }
  }
  if (s.size() > (1u << 20)) s.resize(1u << 20);
  return s;
}

// Tokens of a libFuzzer dictionary: the quoted part of each line, with \\, \" and \xNN unescaped.
std::vector<std::string> read_dictionary(const std::string& file) {
  std::ifstream in(file);
  if (!in) {
    std::cerr << file << ": cannot open the dictionary\n";
    std::exit(2);
  }
  std::vector<std::string> tokens;
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t open = line.find('"'), close = line.rfind('"');
    if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
    std::string token;
    for (std::size_t i = open + 1; i < close; ++i) {
      if (line[i] != '\\' || i + 1 >= close) {
        token += line[i];
      } else if (line[i + 1] == 'x' && i + 3 < close) {
        token += static_cast<char>(std::stoi(line.substr(i + 2, 2), nullptr, 16));
        i += 3;
      } else {
        token += line[++i];
      }
    }
    tokens.push_back(token);
  }
  return tokens;
}

}  // namespace

int main(int argc_in, char** argv_in) {
  std::vector<char*> args;
  std::vector<std::string> tokens;
  for (int i = 0; i < argc_in; ++i) {
    const std::string a = argv_in[i];
    if (a.rfind("-dict=", 0) == 0)
      tokens = read_dictionary(a.substr(6));
    else
      args.push_back(argv_in[i]);
  }
  const int argc = static_cast<int>(args.size());
  char** argv = args.data();
  if (argc < 2) {
    std::cerr << "usage: fuzz_<reader>_replay SEED_DIR [ITERATIONS] [SECONDS] [RANDOM_SEED] [-dict=FILE]\n";
    return 2;
  }
  const long iterations = argc > 2 ? std::atol(argv[2]) : 300000;
  const double seconds = argc > 3 ? std::atof(argv[3]) : 20.0;
  const unsigned long long seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 20261122ULL;
  std::vector<std::string> corpus;
  for (const auto& entry : std::filesystem::directory_iterator(argv[1])) {
    if (!entry.is_regular_file()) continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    corpus.push_back(bytes.str());
  }
  if (corpus.empty()) {
    std::cerr << "no seed files in " << argv[1] << "\n";
    return 1;
  }
  signal(SIGALRM, on_input_timeout);
  for (const auto& c : corpus) run(c);
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long done = 0;
  double slowest = 0.0;
  for (; done < iterations; ++done) {
    if (done % 100 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
      break;
    const std::string input = mutate(corpus[rng() % corpus.size()], corpus, tokens, rng);
    const auto t0 = std::chrono::steady_clock::now();
    run(input);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (took > slowest) {
      slowest = took;
      if (const char* keep = std::getenv("FUZZ_KEEP_SLOWEST")) std::ofstream(keep, std::ios::binary) << input;
    }
  }
  std::cout << "{\"seeds\": " << corpus.size() << ", \"tokens\": " << tokens.size()
            << ", \"mutated_inputs\": " << done << ", \"slowest_input_s\": " << slowest << ", \"seconds\": "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << "}\n";
  return 0;
}
