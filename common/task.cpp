#include "common/task.h"

#include <cstdio>
#include <mutex>
#include <set>
#include <string>

namespace rt {

bool report_unfinished_task(const char* task_id) {
  static std::mutex mutex;
  static std::set<std::string> reported;
  std::lock_guard lock(mutex);
  if (!reported.insert(task_id).second) return false;
  std::fprintf(stderr, "TODO: task %s is not implemented yet (see docs/ for the stage handout)\n",
               task_id);
  return true;
}

}  // namespace rt
