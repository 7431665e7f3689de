#pragma once
// The examples of a protocol document (docs/query-protocol.md, docs/world-protocol.md): the
// pairs of consecutive lines starting with '{' inside ``` blocks without a language tag, a
// request and its answer, with the block they stand in.
#include <fstream>
#include <string>
#include <vector>

namespace proxima::test {

/// One request line of a document and the answer line under it.
struct DocExample {
  std::string request;  ///< the request line
  std::string answer;   ///< the answer line
  int line = 0;         ///< line number of the request in the document
  int block = 0;        ///< which plain code block (0, 1, ...) holds it
};

/// The examples of the document at `path`, in document order: those of the plain code blocks,
/// or with `tag` those of the blocks opened by ```tag (the 2D world's examples: "world2d").
inline std::vector<DocExample> read_doc_examples(const std::string& path, const std::string& tag = "") {
  std::ifstream in(path);
  std::vector<DocExample> examples;
  std::string line;
  bool in_plain_block = false;
  bool in_other_block = false;
  int blocks = 0;
  std::string pending;
  int pending_line = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.rfind("```", 0) == 0) {
      if (in_plain_block || in_other_block) {
        if (in_plain_block) ++blocks;
        in_plain_block = in_other_block = false;
      } else if (line == "```" + tag) {
        in_plain_block = true;
      } else {
        in_other_block = true;
      }
      pending.clear();
      continue;
    }
    if (!in_plain_block || line.empty() || line.front() != '{') {
      pending.clear();
      continue;
    }
    if (pending.empty()) {
      pending = line;
      pending_line = number;
    } else {
      examples.push_back({pending, line, pending_line, blocks});
      pending.clear();
    }
  }
  return examples;
}

}  // namespace proxima::test
