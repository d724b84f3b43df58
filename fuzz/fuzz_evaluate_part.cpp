// Fuzzes the reader of `evaluate --shard K/N` part folders (ste/evaluation_part_reader:
// read_evaluation_part, then check_part_coverage), what `evaluate merge` reads. An input is
// part.json, a NUL byte, runs.csv, a NUL byte, timings.csv, a NUL byte, tracks.json (missing
// parts are empty files); they
// go to a private temporary folder, since the reader takes a folder. part.json carries its own
// SHA-256 and its files', so a mutated input almost never passes them: each input is also read
// resealed (the checksums recomputed) when its part.json is a JSON object, to reach the parsers
// behind them. Bad input must end in InputError; anything else escaping is a bug, and libFuzzer
// reports it as a crash. An accepted part must be consistent: K of N in range, one runs.csv and
// one timings.csv record and one track per run, each run on one of the part's maps.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"
#include "fuzz/scratch_folder.hpp"
#include "run/evaluation_part_reader.hpp"
#include "run/run_tracks.hpp"

namespace fs = std::filesystem;
using plumekit::fuzz::scratch_folder;
using plumekit::fuzz::write_file;
namespace run = plumekit::run;

namespace {

// The next NUL-separated piece of `rest` (all of it when there is no NUL), taken off it.
std::string_view next_piece(std::string_view& rest) {
  const std::size_t nul = rest.find('\0');
  const std::string_view piece = rest.substr(0, nul);
  rest = nul == std::string_view::npos ? std::string_view() : rest.substr(nul + 1);
  return piece;
}

std::size_t records(const std::string& csv) {
  return plumekit::parse_csv(csv, "fuzz").size();
}

void read_folder(std::string_view part, std::string_view runs, std::string_view timings,
                 std::string_view tracks) {
  const fs::path& dir = scratch_folder("part");
  write_file(dir / run::kPartFile, part);
  write_file(dir / "runs.csv", runs);
  write_file(dir / "timings.csv", timings);
  write_file(dir / run::kTracksFile, tracks);
  try {
    const run::EvaluationPart p = run::read_evaluation_part(dir);
    if (p.n < 1 || p.k < 0 || p.k >= p.n) std::abort();
    const std::size_t maps = p.j.at("maps").size();
    for (const run::RunRecord& r : p.runs)
      if (r.map_index < 0 || static_cast<std::size_t>(r.map_index) >= maps) std::abort();
    if (records(p.runs_csv.header + p.runs_csv.body) != p.runs.size() + 1 ||
        records(p.timings_csv.header + p.timings_csv.body) != p.runs.size() + 1 ||
        p.tracks.at("runs").size() != p.runs.size())
      std::abort();
    run::check_part_coverage({p});
  } catch (const plumekit::InputError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  const std::string_view part = next_piece(rest);
  const std::string_view runs = next_piece(rest);
  const std::string_view timings = next_piece(rest);
  const std::string_view tracks = next_piece(rest);
  read_folder(part, runs, timings, tracks);
  // Resealed: the files' checksums and part.json's own recomputed.
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(part, nullptr, false);
  if (!j.is_object()) return 0;
  j["files"] = {{"runs.csv", plumekit::sha256_hex(runs)},
                {"timings.csv", plumekit::sha256_hex(timings)},
                {run::kTracksFile, plumekit::sha256_hex(tracks)}};
  j["sha256"] = run::part_body_sha256(j);
  read_folder(j.dump(2), runs, timings, tracks);
  return 0;
}
