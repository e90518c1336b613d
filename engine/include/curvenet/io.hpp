// curvenet/io.hpp — reading networks, writing networks and meshes.
//
// Formats
//  * native network (.json): documented in docs/network-format.md; read and
//    written exactly (doubles round-trip bit for bit).
//  * .lop loop files: one face, a loop of B-spline curves (first line the
//    number of curves; per curve: degree; knot count and knots; control-point
//    count and x y z triples).
//  * curve graphs: an OBJ with `l` elements and no `f` (a sketch), or a
//    native document with curves and no faces; readNetworkFile finds their
//    network (nodes, fitted curves, faces) by networkFromCurveGraph with the
//    default options (curvenet/sketch.hpp).
//  * meshes: Wavefront OBJ and binary little-endian PLY, both with normals.
//  * mesh input (curvenet approximate, render): OBJ (`v` and `f` records;
//    polygons are fan-triangulated; other records ignored), OFF (ASCII), PLY
//    (ASCII and binary; `vertex` x y z and `face` vertex_indices, other
//    elements and properties skipped) and STL (ASCII and binary; equal
//    corners merged into one vertex).
//
// Errors: every reader throws InputError naming the file, the element or line,
// and what is wrong. Writers never leave a partial file behind: they write to
// a temporary file beside the target and rename it into place when complete.
#pragma once

#include <functional>
#include <iosfwd>
#include <string>

#include "curvenet/mesh.hpp"
#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// Parses a native network document; `file` is only used in error messages.
/// Arrays and objects nested more than 64 deep are refused (the format needs
/// 5), as soon as the parser reaches that depth.
NetworkDescription parseNetworkJson(const std::string &text, const std::string &file = {});
/// The native document for a description (pretty-printed JSON).
std::string networkToJson(const NetworkDescription &description);

/// Parses a .lop loop file into a one-face description.
NetworkDescription parseLop(const std::string &text, const std::string &file = {});

/// Reads a network file, choosing the format by extension (.json, .lop, .obj
/// curve graphs).
NetworkDescription readNetworkFile(const std::string &path);

/// Resolves a command-line INPUT: "builtin:NAME" or a file path.
NetworkDescription loadNetworkInput(const std::string &input);

/// Writes the file at `path` through `writer`, atomically: the content goes
/// to a temporary file in the same folder which is renamed onto `path` only
/// after `writer` returned and the stream flushed without error. On any
/// exception the temporary is removed and the exception propagates.
void writeFileAtomically(const std::string &path, const std::function<void(std::ostream &)> &writer);

/// The whole file as bytes; InputError naming the file and the system's reason.
std::string readTextFile(const std::string &path);

/// Triangle meshes for input: positions and triangles only (normals, texture
/// coordinates and groups are dropped; polygons are fan-triangulated).
/// InputError names the file and line: a malformed number, an index out of
/// range, a face with fewer than 3 corners, no triangles at all.
Mesh parseObjMesh(const std::string &text, const std::string &file = {});
Mesh parseOffMesh(const std::string &text, const std::string &file = {});
Mesh parsePlyMesh(const std::string &text, const std::string &file = {});
Mesh parseStlMesh(const std::string &text, const std::string &file = {});
/// A mesh in any of the formats above, recognised from the content ("ply",
/// "OFF", "solid" or binary bytes for STL, OBJ otherwise): for standard input.
Mesh parseMeshText(const std::string &text, const std::string &file = {});
/// Reads .obj, .off, .ply or .stl by extension.
Mesh readMeshFile(const std::string &path);

/// OBJ text: `v` lines, `vn` lines when the mesh has normals (faces then
/// `f a//a b//b c//c`), each double in its shortest round-trip form, so a
/// reader gets the same doubles back. Formatted on all threads (TBB) in
/// chunks, written in order; memory beyond the mesh: a few MB per thread.
void writeObj(const Mesh &mesh, std::ostream &out);
/// Binary little-endian PLY: float64 positions (and normals), uint32 triangles.
void writePly(const Mesh &mesh, std::ostream &out);
/// Writes OBJ or PLY by the extension of `path` (atomically).
void writeMeshFile(const Mesh &mesh, const std::string &path);

} // namespace v1
} // namespace curvenet
