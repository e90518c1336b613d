// Curve graphs from files: OBJ polylines / edge soups, and the curves of a
// description sampled into strokes.
#include <cctype>
#include <filesystem>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "curvenet/error.hpp"
#include "curvenet/io.hpp"
#include "../io/text_tokens.hpp"
#include "curvenet/sketch.hpp"

namespace curvenet {
inline namespace v1 {
namespace {

/// Calls visit(lineNumber, tokens) for every non-empty line, comments removed.
template <typename Visit> void forEachRecord(const std::string &text, Visit &&visit) {
  const std::vector<std::string_view> all = text::lines(text);
  for (std::size_t k = 0; k < all.size(); ++k)
    if (const auto t = text::tokens(all[k]); !t.empty()) visit(k + 1, t);
}

} // namespace

bool objIsCurveGraph(const std::string &text) {
  bool lines = false, faces = false;
  forEachRecord(text, [&](std::size_t, const std::vector<std::string_view> &t) {
    lines = lines || t[0] == "l";
    faces = faces || t[0] == "f";
  });
  return lines && !faces;
}

CurveGraph parseObjCurveGraph(const std::string &text, const std::string &file) {
  CurveGraph graph;
  struct PendingStroke {
    std::vector<long long> indices;
    std::size_t line;
  };
  std::vector<PendingStroke> pending;
  forEachRecord(text, [&](std::size_t line, const std::vector<std::string_view> &t) {
    const std::string where = "line " + std::to_string(line);
    if (t[0] == "v") {
      if (t.size() < 4) throw InputError(file, where, "a vertex needs x y z");
      graph.points.push_back(
          {text::number(t[1], file, where), text::number(t[2], file, where), text::number(t[3], file, where)});
    } else if (t[0] == "l") {
      if (t.size() < 3) throw InputError(file, where, "a line element needs at least 2 points");
      PendingStroke stroke{{}, line};
      // "i" or "i/t"; negative indices count back from the last vertex read.
      for (std::size_t k = 1; k < t.size(); ++k) {
        const long long index = text::integer(t[k].substr(0, t[k].find('/')), file, where);
        if (index == 0) throw InputError(file, where, "OBJ indices start at 1");
        stroke.indices.push_back(index < 0 ? static_cast<long long>(graph.points.size()) + index : index - 1);
      }
      pending.push_back(std::move(stroke));
    } else if (t[0] == "f") {
      throw InputError(file, where, "a face record in a curve graph (an OBJ with faces is a triangle mesh)");
    }
    // vn, vt, o, g, s, usemtl, mtllib: nothing the graph uses.
  });
  for (const PendingStroke &stroke : pending) {
    std::vector<int> chain;
    for (long long index : stroke.indices) {
      if (index < 0 || index >= static_cast<long long>(graph.points.size()))
        throw InputError(file, "line " + std::to_string(stroke.line),
                         "vertex index " + std::to_string(index + 1) + " out of range (" +
                             std::to_string(graph.points.size()) + " vertices)");
      chain.push_back(static_cast<int>(index));
    }
    graph.strokes.push_back(std::move(chain));
    graph.strokeNames.push_back("line " + std::to_string(stroke.line));
  }
  if (graph.strokes.empty()) throw InputError(file, {}, "no line elements: not a curve graph");
  return graph;
}

CurveGraph curveGraphFromCurves(const NetworkDescription &description, int samples) {
  CurveGraph graph;
  graph.name = description.name;
  for (std::size_t c = 0; c < description.curves.size(); ++c) {
    const BSplineCurve &curve = description.curves[c];
    std::vector<int> chain;
    if (curve.degree() == 1 && !curve.isRational()) {
      // A polyline: its corners are the samples, fitted afresh (a degree-1
      // curve would render as shards).
      for (const Vec3 &p : curve.controlPoints()) {
        chain.push_back(static_cast<int>(graph.points.size()));
        graph.points.push_back(p);
      }
    } else {
      const double a = curve.domainStart(), b = curve.domainEnd();
      for (int k = 0; k < samples; ++k) {
        chain.push_back(static_cast<int>(graph.points.size()));
        graph.points.push_back(curve.point(a + (b - a) * k / (samples - 1)));
      }
    }
    graph.strokes.push_back(std::move(chain));
    graph.strokeNames.push_back("curve " + std::to_string(c));
  }
  return graph;
}

CurveGraph readCurveGraphFile(const std::string &path) {
  CurveGraph graph = parseObjCurveGraph(readTextFile(path), path);
  graph.name = std::filesystem::path(path).stem().string();
  return graph;
}

} // namespace v1
} // namespace curvenet
