// Reading the rank and rendezvous from the environment (see env.h).
#include "layers/dist/env.h"

#include <cstdlib>
#include <optional>
#include <string>

#include "layers/core/error.h"
#include "layers/core/whole_number.h"

namespace layers::dist {
namespace {

constexpr const char* kSource = "environment";

// A decimal integer in [lo, hi]; InputError naming the variable otherwise.
long parse_int(const char* name, const char* text, long lo, long hi, const std::string& expected) {
  const std::optional<long long> v = parse_whole_number(text, hi);
  if (!v || *v < lo) throw InputError(kSource, name, expected, "'" + std::string(text) + "'");
  return static_cast<long>(*v);
}

std::string range(long lo, long hi_exclusive, const std::string& why = "") {
  return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi_exclusive) + ")" + why;
}

}  // namespace

std::string first_node(const std::string& nodelist, const std::string& field) {
  if (nodelist.empty()) throw InputError(kSource, field, "a Slurm node list such as node[01-04,07]", "''");
  std::string out;
  int depth = 0;
  bool in_first = true;  // inside a bracket: still in its first range or name
  for (char c : nodelist) {
    if (c == '[') {
      if (depth++ > 0) break;
      in_first = true;
    } else if (c == ']') {
      if (--depth < 0) break;
    } else if (depth == 0) {
      if (c == ',') break;  // the next host
      out += c;
    } else if (c == ',' || c == '-') {
      in_first = false;  // a range's end or the bracket's next item
    } else if (in_first) {
      out += c;
    }
  }
  bool balanced = true;
  {
    int d = 0;
    for (char c : nodelist) {
      d += c == '[' ? 1 : c == ']' ? -1 : 0;
      balanced = balanced && d >= 0 && d <= 1;
    }
    balanced = balanced && d == 0;
  }
  if (!balanced || out.empty())
    throw InputError(kSource, field, "a Slurm node list such as node[01-04,07]", "'" + nodelist + "'");
  return out;
}

std::optional<DistEnv> read_env(const EnvLookup& get) {
  DistEnv e;
  const char* world = get("WORLD_SIZE");
  const char* slurm_tasks = get("SLURM_NTASKS");
  if (!world && get("RANK"))
    throw InputError(kSource, "WORLD_SIZE", "set together with RANK (as torchrun sets them)", "unset");
  if (world) {
    e.launcher = "torchrun";
    e.world_size = static_cast<int>(parse_int("WORLD_SIZE", world, 1, 65536, "an integer in [1, 65536]"));
    if (e.world_size == 1) return std::nullopt;
    const char* rank = get("RANK");
    if (!rank) throw InputError(kSource, "RANK", range(0, e.world_size, " (WORLD_SIZE is set)"), "unset");
    e.rank = static_cast<int>(parse_int("RANK", rank, 0, e.world_size - 1, range(0, e.world_size, " (WORLD_SIZE)")));
    const char* local = get("LOCAL_RANK");
    e.local_rank = local ? static_cast<int>(parse_int("LOCAL_RANK", local, 0, e.world_size - 1,
                                                      range(0, e.world_size, " (WORLD_SIZE)")))
                         : 0;
  } else if (slurm_tasks) {
    e.launcher = "slurm";
    e.world_size = static_cast<int>(parse_int("SLURM_NTASKS", slurm_tasks, 1, 65536, "an integer in [1, 65536]"));
    if (e.world_size == 1) return std::nullopt;
    const char* rank = get("SLURM_PROCID");
    if (!rank) throw InputError(kSource, "SLURM_PROCID", range(0, e.world_size, " (SLURM_NTASKS is set)"), "unset");
    e.rank = static_cast<int>(
        parse_int("SLURM_PROCID", rank, 0, e.world_size - 1, range(0, e.world_size, " (SLURM_NTASKS)")));
    const char* local = get("SLURM_LOCALID");
    e.local_rank = local ? static_cast<int>(parse_int("SLURM_LOCALID", local, 0, e.world_size - 1,
                                                      range(0, e.world_size, " (SLURM_NTASKS)")))
                         : 0;
  } else {
    return std::nullopt;
  }

  if (const char* addr = get("MASTER_ADDR")) {
    e.master_addr = addr;
    if (e.master_addr.empty()) throw InputError(kSource, "MASTER_ADDR", "the host name or address of rank 0", "''");
  } else if (e.launcher == "slurm") {
    const char* list = get("SLURM_JOB_NODELIST");
    const char* field = "SLURM_JOB_NODELIST";
    if (!list) list = get("SLURM_NODELIST"), field = "SLURM_NODELIST";
    if (!list)
      throw InputError(kSource, "MASTER_ADDR", "the host of rank 0 (or SLURM_JOB_NODELIST to take it from)", "unset");
    e.master_addr = first_node(list, field);
  } else {
    throw InputError(kSource, "MASTER_ADDR", "the host name or address of rank 0 (WORLD_SIZE > 1)", "unset");
  }

  if (const char* port = get("MASTER_PORT")) {
    e.master_port = static_cast<int>(parse_int("MASTER_PORT", port, 1, 65535, "a TCP port in [1, 65535]"));
  } else if (e.launcher == "slurm" && get("SLURM_JOB_ID")) {
    const long job = parse_int("SLURM_JOB_ID", get("SLURM_JOB_ID"), 0, 999999999999L, "a Slurm job id");
    e.master_port = static_cast<int>(29500 + job % 10000);
  } else {
    throw InputError(kSource, "MASTER_PORT", "a TCP port in [1, 65535] (WORLD_SIZE > 1)", "unset");
  }
  return e;
}

std::optional<DistEnv> read_env() {
  return read_env([](const char* name) -> const char* { return std::getenv(name); });
}

}  // namespace layers::dist
