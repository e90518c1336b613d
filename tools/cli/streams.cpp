// File arguments of the subcommands: a path, or `-` for standard input or
// output. What comes through a pipe has no extension: a network or a mesh on
// standard input is recognised by its first word, an output names its format
// with --format.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string_view>

#include "commands.hpp"
#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "curvenet/sketch.hpp"
#include "curvenet/surface.hpp"

namespace curvenet::cli {

namespace {

constexpr const char *kStandardInput = "standard input";

/// The first word of `text` after white space (at most 16 characters).
std::string firstWord(const std::string &text) {
  std::size_t start = 0;
  while (start < text.size() && std::isspace(static_cast<unsigned char>(text[start]))) ++start;
  std::size_t end = start;
  while (end < text.size() && end - start < 16 && !std::isspace(static_cast<unsigned char>(text[end]))) ++end;
  return text.substr(start, end - start);
}

void writeMeshAs(const Mesh &mesh, const std::string &format, std::ostream &out) {
  if (format == ".obj") writeObj(mesh, out);
  else writePly(mesh, out);
}

} // namespace

bool standardInputIsNetwork() {
  const std::string word = firstWord(readStandardInput());
  const std::string &text = readStandardInput();
  return word.starts_with("{") || (!word.empty() && std::isdigit(static_cast<unsigned char>(word[0]))) ||
         objIsCurveGraph(text);
}

NetworkDescription loadNetworkArgument(const std::string &input) {
  if (!isStandardStream(input)) return loadNetworkInput(input);
  const std::string &text = readStandardInput();
  // A native document is a JSON object; a .lop file starts with its curve count.
  if (firstWord(text).starts_with("{")) {
    NetworkDescription network = parseNetworkJson(text, kStandardInput);
    if (network.name.empty()) network.name = "stdin";
    return network;
  }
  // An OBJ of polylines (`l` elements, no `f`) is a curve graph: its faces are found.
  if (objIsCurveGraph(text))
    return networkFromCurveGraph(parseObjCurveGraph(text, kStandardInput), {}, kStandardInput).description;
  return parseLop(text, kStandardInput);
}

Mesh readMeshArgument(const std::string &input) {
  if (!isStandardStream(input)) return readMeshFile(input);
  const std::string &text = readStandardInput();
  return parseMeshText(text, kStandardInput);
}

void checkMeshOutput(const std::string &path, const std::string &format, const std::string &what) {
  const std::string ext = fileFormat(path, format, what);
  if (ext != ".obj" && ext != ".ply")
    throw InputError(isStandardStream(path) ? "" : path, what,
                     "unknown mesh format \"" + ext + "\" (expected .obj or .ply, or --format obj|ply)");
}

void writeMeshArgument(const Mesh &mesh, const std::string &path, const std::string &format) {
  const std::string ext = fileFormat(path, format, "--output");
  if (isStandardStream(path)) {
    writeMeshAs(mesh, ext, std::cout);
    std::cout.flush();
    if (!std::cout) throw InputError("-", {}, "cannot write the mesh to standard output");
    return;
  }
  if (format.empty()) return writeMeshFile(mesh, path);
  writeFileAtomically(path, [&](std::ostream &out) { writeMeshAs(mesh, ext, out); });
}

Surface buildSurface(const Network &network, const SurfaceOptions &options, const std::string &input) {
  return namingInput(input, [&] { return Surface::build(network, options); });
}

void createOutputFolder(const std::string &folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (!error && !std::filesystem::is_directory(folder, error)) throw InputError(folder, {}, "exists and is not a folder");
  if (error) throw InputError(folder, {}, "cannot create the output folder: " + error.message());
}

std::FILE *summaryStream(const std::string &output) { return isStandardStream(output) ? stderr : stdout; }

} // namespace curvenet::cli
