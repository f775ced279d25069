// Support for the student starter tree (docs/solution-markers.md). A placeholder that stands in for
// an unwritten task calls report_unfinished_task("stage1.sphere.stable") and then returns something
// harmless, so one missing task never crashes the program or blocks the tasks after it.
#pragma once

namespace rt {

// Prints "TODO: task <id> is not implemented yet" to stderr, once per task id per process;
// thread-safe. Returns true the first time it is called for an id. The id must stay valid for the
// whole run, as a string literal does (a placeholder writes it so): its address is remembered, so
// that later calls cost one lookup (common/task.cpp).
bool report_unfinished_task(const char* task_id);

}  // namespace rt
