// curvenet_figures — the deterministic tables of README.md and docs/*.md,
// from the build.
//
//   curvenet_figures [--repo DIR] [--only NAME,...]            print every table
//   curvenet_figures [--repo DIR] [--only NAME,...] --check    compare with the documents
//   curvenet_figures [--repo DIR] [--only NAME,...] --update   rewrite the tables in the documents
//
// A table stands in a document between `<!-- figures:NAME -->` and
// `<!-- /figures -->`. `--check` exits 1 when a table differs from what the
// build computes (a hand edit, or a change to the code that moves a figure),
// naming the document, the line and both texts. Exit 2: usage or document
// structure errors (an unknown table name, an unterminated block).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "tables.hpp"

namespace fs = std::filesystem;
using curvenet::figures::Table;

namespace {

constexpr const char *kUpdateCommand = "bash tools/scripts/figures.sh --update";

struct Document {
  fs::path path;
  std::vector<std::string> lines;
};

/// One `<!-- figures:NAME -->` … `<!-- /figures -->` block: lines (first, last) exclusive of the markers.
struct Block {
  Document *document = nullptr;
  std::string name;
  size_t first = 0, end = 0; ///< content lines [first, end)
};

std::vector<Document> readDocuments(const fs::path &repository) {
  std::vector<fs::path> paths = {repository / "README.md"};
  std::vector<fs::path> docs;
  for (const fs::directory_entry &entry : fs::directory_iterator(repository / "docs"))
    if (entry.path().extension() == ".md") docs.push_back(entry.path());
  std::sort(docs.begin(), docs.end());
  paths.insert(paths.end(), docs.begin(), docs.end());
  std::vector<Document> documents;
  for (const fs::path &path : paths) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path.string());
    Document document{path, {}};
    for (std::string line; std::getline(in, line);) document.lines.push_back(line);
    documents.push_back(std::move(document));
  }
  return documents;
}

std::string where(const Document &document, size_t line) {
  return document.path.filename().string() + ":" + std::to_string(line + 1);
}

std::vector<Block> findBlocks(std::vector<Document> &documents) {
  static const std::string open = "<!-- figures:", close = "<!-- /figures -->";
  std::vector<Block> blocks;
  for (Document &document : documents)
    for (size_t i = 0; i < document.lines.size(); ++i) {
      const std::string &line = document.lines[i];
      if (line == close) throw std::runtime_error(where(document, i) + ": <!-- /figures --> without an opening marker");
      if (!line.starts_with(open)) continue;
      const size_t nameEnd = line.find(" -->");
      if (nameEnd == std::string::npos || nameEnd + 4 != line.size())
        throw std::runtime_error(where(document, i) + ": expected <!-- figures:NAME -->");
      Block block{&document, line.substr(open.size(), nameEnd - open.size()), i + 1, i + 1};
      while (block.end < document.lines.size() && document.lines[block.end] != close) {
        if (document.lines[block.end].starts_with(open))
          throw std::runtime_error(where(document, block.end) + ": table \"" + block.name + "\" is not closed");
        ++block.end;
      }
      if (block.end == document.lines.size())
        throw std::runtime_error(where(document, i) + ": table \"" + block.name + "\" is not closed");
      blocks.push_back(block);
      i = block.end;
    }
  return blocks;
}

std::string firstCell(const std::string &line) {
  if (!line.starts_with("|")) return {};
  const size_t end = line.find('|', 1);
  return end == std::string::npos ? std::string() : line.substr(0, end + 1);
}

/// The block's content once `table` is written into it: all of it for a
/// plain table; for a keyed one, its own rows replaced (appended when
/// missing) and every other line kept.
std::vector<std::string> contentWith(const Block &block, const Table &table) {
  if (!table.keyed) return table.lines;
  std::vector<std::string> content(block.document->lines.begin() + long(block.first),
                                   block.document->lines.begin() + long(block.end));
  for (const std::string &line : table.lines) {
    auto same = std::find_if(content.begin(), content.end(),
                             [&](const std::string &old) { return firstCell(old) == firstCell(line); });
    if (same != content.end()) *same = line;
    else content.push_back(line);
  }
  return content;
}

/// Prints where `block` differs from `wanted`; true when it does.
bool reportDifference(const Block &block, const std::vector<std::string> &wanted) {
  const std::vector<std::string> &lines = block.document->lines;
  const size_t have = block.end - block.first;
  for (size_t k = 0; k < std::max(have, wanted.size()); ++k) {
    const std::string *old = k < have ? &lines[block.first + k] : nullptr;
    const std::string *now = k < wanted.size() ? &wanted[k] : nullptr;
    if (old && now && *old == *now) continue;
    std::printf("%s: table \"%s\" differs from the build\n  document: %s\n  build:    %s\n",
                where(*block.document, block.first + k).c_str(), block.name.c_str(), old ? old->c_str() : "(no line)",
                now ? now->c_str() : "(no line)");
    return true;
  }
  return false;
}

void writeDocument(const Document &document) {
  const fs::path temporary = document.path.string() + ".figures-new";
  {
    std::ofstream out(temporary);
    for (const std::string &line : document.lines) out << line << "\n";
    if (!out) throw std::runtime_error("cannot write " + temporary.string());
  }
  fs::rename(temporary, document.path);
}

struct Arguments {
  fs::path repository = CURVENET_SOURCE_DIR;
  std::vector<std::string> only;
  bool check = false, update = false;
};

std::optional<Arguments> parseArguments(int argc, char **argv) {
  Arguments arguments;
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "--check") arguments.check = true;
    else if (word == "--update") arguments.update = true;
    else if (word == "--repo" && i + 1 < argc) arguments.repository = argv[++i];
    else if (word == "--only" && i + 1 < argc) {
      std::istringstream names(argv[++i]);
      for (std::string name; std::getline(names, name, ',');) arguments.only.push_back(name);
    } else return std::nullopt;
  }
  if (arguments.check && arguments.update) return std::nullopt;
  return arguments;
}

int run(const Arguments &arguments) {
  std::vector<std::string> names = arguments.only.empty() ? curvenet::figures::tableNames() : arguments.only;
  const std::vector<std::string> known = curvenet::figures::tableNames();
  curvenet::figures::TableMaker tables(arguments.repository);
  std::vector<Document> documents = readDocuments(arguments.repository);
  const std::vector<Block> blocks = findBlocks(documents);
  for (const Block &block : blocks)
    if (std::find(known.begin(), known.end(), block.name) == known.end())
      throw std::runtime_error(where(*block.document, block.first - 1) + ": no table named \"" + block.name + "\"");
  if (!arguments.check && !arguments.update) {
    for (const std::string &name : names) {
      std::printf("<!-- figures:%s -->\n", name.c_str());
      for (const std::string &line : tables.compute(name).lines)
        std::printf("%s\n", line.c_str());
      std::printf("<!-- /figures -->\n\n");
    }
    return 0;
  }
  bool differs = false;
  std::map<Document *, std::vector<std::pair<Block, std::vector<std::string>>>> rewrites;
  for (const std::string &name : names) {
    const Table table = tables.compute(name);
    bool shown = false;
    for (const Block &block : blocks) {
      if (block.name != name) continue;
      shown = true;
      std::vector<std::string> wanted = contentWith(block, table);
      if (arguments.check) differs = reportDifference(block, wanted) || differs;
      else rewrites[block.document].push_back({block, std::move(wanted)});
    }
    if (!shown) {
      std::printf("table \"%s\" stands in no document (README.md, docs/*.md)\n", name.c_str());
      differs = true;
    }
  }
  for (auto &[document, changes] : rewrites) {
    // From the last block up, so the earlier blocks' line numbers stay valid.
    std::sort(changes.begin(), changes.end(), [](const auto &a, const auto &b) { return a.first.first > b.first.first; });
    for (const auto &[block, content] : changes) {
      document->lines.erase(document->lines.begin() + long(block.first), document->lines.begin() + long(block.end));
      document->lines.insert(document->lines.begin() + long(block.first), content.begin(), content.end());
    }
    writeDocument(*document);
  }
  if (differs && arguments.check)
    std::printf("The tables above do not match the build. If the change that moved them is meant, run\n  %s\n"
                "and commit the documents it rewrites (review the figures first).\n",
                kUpdateCommand);
  return differs ? 1 : 0;
}

} // namespace

int main(int argc, char **argv) {
  const std::optional<Arguments> arguments = parseArguments(argc, argv);
  if (!arguments) {
    std::fprintf(stderr, "usage: curvenet_figures [--repo DIR] [--only NAME,...] [--check | --update]\n");
    return 2;
  }
  try {
    return run(*arguments);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "curvenet_figures: %s\n", e.what());
    return 2;
  }
}
