// A small mutation fuzzer for gcc builds (`make test`): replays the seed corpus, then feeds mutated seeds
// (bit flips, byte edits, cuts, duplicated and spliced ranges, DXF tokens) through the same entry point as
// the libFuzzer target, until an iteration count or a time budget runs out.
// Usage: fuzz_dxf_replay SEED_DIR [ITERATIONS] [SECONDS] [RANDOM_SEED]
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

int run(const std::string& bytes) {
  return LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

std::string mutate(std::string s, const std::vector<std::string>& corpus, std::mt19937_64& rng) {
  static const std::vector<std::string> tokens = {"0\n",
                                                  "\n0\nINSERT\n2\nB\n",
                                                  "\n0\nBLOCK\n2\nB\n",
                                                  "\n0\nENDBLK\n",
                                                  "\n0\nLWPOLYLINE\n90\n",
                                                  "\n42\n",
                                                  "1e308",
                                                  "-1e308",
                                                  "nan",
                                                  "999999",
                                                  "-999999",
                                                  "\n0\nEOF\n",
                                                  "\n0\nSECTION\n",
                                                  "\n0\nENDSEC\n",
                                                  "\n70\n",
                                                  "\n0\nSPLINE\n71\n",
                                                  "\n41\n0\n",
                                                  "\n230\n-1\n",
                                                  "\r\n",
                                                  "\n0\nVERTEX\n",
                                                  "\n0\nSEQEND\n",
                                                  "\n50\n90\n",
                                                  "\n44\n1e-300\n",
                                                  "\n71\n1000\n",
                                                  "\n0\nPOLYLINE\n"};
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
        s.insert(pos(s.size()), tokens[rng() % tokens.size()]);
        break;
    }
  }
  if (s.size() > (1u << 20)) s.resize(1u << 20);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: fuzz_dxf_replay SEED_DIR [ITERATIONS] [SECONDS] [RANDOM_SEED]\n";
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
  for (const auto& c : corpus) run(c);
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  long done = 0;
  double slowest = 0.0;
  for (; done < iterations; ++done) {
    if (done % 1000 == 0 &&
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
      break;
    const std::string input = mutate(corpus[rng() % corpus.size()], corpus, rng);
    const auto t0 = std::chrono::steady_clock::now();
    run(input);
    const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (took > slowest) {
      slowest = took;
      if (const char* keep = std::getenv("FUZZ_KEEP_SLOWEST")) std::ofstream(keep, std::ios::binary) << input;
    }
  }
  std::cout << "{\"seeds\": " << corpus.size() << ", \"mutated_inputs\": " << done
            << ", \"slowest_input_s\": " << slowest << ", \"seconds\": "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << "}\n";
  return 0;
}
