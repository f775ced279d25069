"""The grader's parts (tools/grade.py): build and test a tree, score it from the manifest, check its
renders against references by statistics, and write the reports. docs/instructors.md explains it."""
