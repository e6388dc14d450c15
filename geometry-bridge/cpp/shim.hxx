// C++ side of tetrafoil-occt's own cxx bridge: what opencascade-sys does not expose.
// Every function that can reach OCCT code which throws returns Result on the Rust side; the
// trycatch below turns OCCT's Standard_Failure (not a std::exception) into that error text.
#pragma once

#include <Standard_Failure.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ShapeMapHasher.hxx>
#include <TCollection_AsciiString.hxx>
#include <NCollection_DataMap.hxx>
#include <Geom_Surface.hxx>
#include <Geom_Curve.hxx>
#include <Geom2d_Curve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom2dAdaptor_Curve.hxx>

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "rust/cxx.h"

namespace rust {
namespace behavior {
template <typename Try, typename Fail>
static void trycatch(Try &&func, Fail &&fail) noexcept {
  try {
    func();
  } catch (const Standard_Failure &e) {
    std::string msg = std::string(e.DynamicType()->Name()) + ": " +
                      (e.GetMessageString() ? e.GetMessageString() : "");
    fail(msg);
  } catch (const std::exception &e) {
    fail(e.what());
  } catch (...) {
    fail("unknown C++ exception");
  }
}
} // namespace behavior
} // namespace rust

namespace tfo {

struct Topology;
struct SewStats;
struct BuildStats;
struct BodyStats;

using NameMap =
    NCollection_DataMap<TopoDS_Shape, TCollection_AsciiString, TopTools_ShapeMapHasher>;

// A shape with its sub-shapes numbered once (TopExp::MapShapes), so ids stay stable for the
// lifetime of the object, plus names (from XDE) keyed by sub-shape (location-aware, orientation
// ignored).
class ShapeIndex {
public:
  explicit ShapeIndex(const TopoDS_Shape &s);
  TopoDS_Shape shape;
  TopTools_IndexedMapOfShape vertices, edges, faces, shells, solids;
  NameMap names;
};

// A face's surface: an independent deep copy of its Geom_Surface with the face location baked
// in, plus the projector that caches data about that copy. Nothing else references either.
// `adaptor` evaluates through OCCT's per-span polynomial cache (a B-spline's D2 otherwise runs
// de Boor from scratch at every call); it is created on first use and, like everything here,
// only ever touched under the Rust handle's Mutex.
class SurfaceGeom {
public:
  Handle(Geom_Surface) surface;
  ShapeAnalysis_Surface analysis;
  double u0, u1, v0, v1;
  mutable std::unique_ptr<GeomAdaptor_Surface> adaptor;
  explicit SurfaceGeom(const Handle(Geom_Surface) &s);
};

// An edge's 3-D curve: deep copy with the edge location baked in, and the edge's range; the
// evaluation cache as for surfaces.
class CurveGeom {
public:
  Handle(Geom_Curve) curve;
  double first, last;
  mutable std::unique_ptr<GeomAdaptor_Curve> adaptor;
};

// One edge use's pcurve in its face's parameter plane: deep copy, and the use's range; the
// evaluation cache as for surfaces.
class PcurveGeom {
public:
  Handle(Geom2d_Curve) curve;
  double first, last;
  mutable std::unique_ptr<Geom2dAdaptor_Curve> adaptor;
};

// Reading (read.cxx).
void quiet_messages();
// status: 0 ok, 1 unreadable, 2 nothing transferred.
std::unique_ptr<ShapeIndex> read_step_xde(rust::Str path, int32_t &status);
std::unique_ptr<ShapeIndex> index_shape(const TopoDS_Shape &shape);
std::unique_ptr<TopoDS_Shape> sub_shape(const ShapeIndex &idx, int32_t kind, int32_t i);

// Topology (topology.cxx).
void extract_topology(const ShapeIndex &idx, Topology &out);

// Repair (repair.cxx).
std::unique_ptr<ShapeIndex> sew_shape(const ShapeIndex &idx, double tolerance, SewStats &stats);
std::unique_ptr<ShapeIndex> heal_shape(const ShapeIndex &idx, double tolerance);
std::unique_ptr<ShapeIndex> fuse_solids(const ShapeIndex &idx, double fuzzy);
std::unique_ptr<ShapeIndex> solids_only(const ShapeIndex &idx);

// Flow domain around a body (farfield.cxx).
std::unique_ptr<ShapeIndex> farfield_domain(const ShapeIndex &body, int kind,
                                            rust::Slice<const double> centre,
                                            rust::Slice<const double> half, int axis, double plane,
                                            int side, double fuzzy);

// Geometry (geometry.cxx).
std::unique_ptr<SurfaceGeom> face_surface(const ShapeIndex &idx, int32_t face);
std::unique_ptr<SurfaceGeom> surface_clone(const SurfaceGeom &g);
void surface_info(const SurfaceGeom &g, rust::Slice<double> out);
void surface_d2(const SurfaceGeom &g, double u, double v, rust::Slice<double> out);
bool surface_project(SurfaceGeom &g, rust::Slice<const double> p, bool has_hint,
                     rust::Slice<double> out);
rust::Vec<double> surface_intersect_circle(const SurfaceGeom &g, rust::Slice<const double> c);

std::unique_ptr<CurveGeom> edge_curve(const ShapeIndex &idx, int32_t edge);
std::unique_ptr<CurveGeom> curve_clone(const CurveGeom &g);
void curve_range(const CurveGeom &g, rust::Slice<double> out);
void curve_d2(const CurveGeom &g, double t, rust::Slice<double> out);
bool curve_project(const CurveGeom &g, rust::Slice<const double> p, bool has_hint, double hint,
                   rust::Slice<double> out);

std::unique_ptr<PcurveGeom> use_pcurve(const ShapeIndex &idx, int32_t face, int32_t loop,
                                       int32_t use);
// Face area (kind 2) or solid volume (kind 4) by BRepGProp's adaptive integration.
double adaptive_measure(const ShapeIndex &idx, int32_t kind, int32_t i, double eps);
std::unique_ptr<PcurveGeom> pcurve_clone(const PcurveGeom &g);
void pcurve_range(const PcurveGeom &g, rust::Slice<double> out);
void pcurve_d2(const PcurveGeom &g, double t, rust::Slice<double> out);

// Construction (build.cxx). points: x, y, z of every section point, sections one after the
// other; counts: points per section; bounds: box lo then hi.
void wing_in_box(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                 rust::Slice<const double> bounds, rust::Str path, BuildStats &stats);
// Planar polygons (points as above, counts per polygon) written as loose STEP faces.
void loose_polygons(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                    rust::Str path);
// A solid written as STEP through XDE with its name and one name per face (in TopExp
// order), the header fixed so a rebuilt sample has the same bytes (build.cxx).
void write_named_solid(const TopoDS_Solid &solid, const char *solid_name,
                       const std::vector<std::string> &face_names, rust::Str path);
// A body fused from lofted parts (body.cxx): sections as above, grouped into parts by
// sections_per_part; part_flags bit 0 ring sections (periodic), bit 1 a nose vertex, bit 2 a
// tail vertex (tips: nose xyz then tail xyz per part); names one per line; half: cut to y >= 0.
void lofted_body(rust::Slice<const double> points, rust::Slice<const int32_t> counts,
                 rust::Slice<const int32_t> sections_per_part,
                 rust::Slice<const int32_t> part_flags, rust::Slice<const double> tips,
                 rust::Str names, bool half, rust::Str path, BodyStats &stats);

// Shared helper: a forward-oriented face's loops, outer first, edges in wire order with their
// orientation relative to that forward face.
std::vector<std::vector<TopoDS_Shape>> face_loops(const TopoDS_Shape &face);

} // namespace tfo
