// Topology extraction into the plain records of the Rust side (ffi.rs shared structs).
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>

namespace tfo {

std::vector<std::vector<TopoDS_Shape>> face_loops(const TopoDS_Shape &face_in) {
  TopoDS_Face face = TopoDS::Face(face_in.Oriented(TopAbs_FORWARD));
  std::vector<TopoDS_Shape> wires;
  TopoDS_Wire outer = BRepTools::OuterWire(face);
  if (!outer.IsNull()) {
    wires.push_back(outer);
  }
  for (TopExp_Explorer ex(face, TopAbs_WIRE); ex.More(); ex.Next()) {
    if (outer.IsNull() || !ex.Current().IsSame(outer)) {
      wires.push_back(ex.Current());
    }
  }
  std::vector<std::vector<TopoDS_Shape>> loops;
  for (const TopoDS_Shape &w : wires) {
    std::vector<TopoDS_Shape> ordered;
    for (BRepTools_WireExplorer wex(TopoDS::Wire(w), face); wex.More(); wex.Next()) {
      ordered.push_back(wex.Current());
    }
    std::vector<TopoDS_Shape> stored;
    for (TopExp_Explorer ex(w, TopAbs_EDGE); ex.More(); ex.Next()) {
      stored.push_back(ex.Current());
    }
    // The wire explorer follows connectivity and may drop edges of a badly connected wire;
    // then the stored order is the honest answer.
    std::vector<TopoDS_Shape> &loop = ordered.size() == stored.size() ? ordered : stored;
    if (!loop.empty()) {
      loops.push_back(loop);
    }
  }
  return loops;
}

namespace {

rust::String surface_kind(const TopoDS_Face &face) {
  switch (BRepAdaptor_Surface(face, false).GetType()) {
  case GeomAbs_Plane: return "plane";
  case GeomAbs_Cylinder: return "cylinder";
  case GeomAbs_Cone: return "cone";
  case GeomAbs_Sphere: return "sphere";
  case GeomAbs_Torus: return "torus";
  case GeomAbs_BezierSurface: return "bezier";
  case GeomAbs_BSplineSurface: return "bspline";
  case GeomAbs_SurfaceOfRevolution: return "revolution";
  case GeomAbs_SurfaceOfExtrusion: return "extrusion";
  case GeomAbs_OffsetSurface: return "offset";
  default: return "other";
  }
}

int32_t index_of(const TopTools_IndexedMapOfShape &m, const TopoDS_Shape &s) {
  return m.FindIndex(s) - 1;
}

} // namespace

void extract_topology(const ShapeIndex &idx, Topology &out) {
  for (int i = 1; i <= idx.vertices.Extent(); ++i) {
    const TopoDS_Vertex &v = TopoDS::Vertex(idx.vertices.FindKey(i));
    gp_Pnt p = BRep_Tool::Pnt(v);
    out.vertices.push_back(VertexRec{p.X(), p.Y(), p.Z(), BRep_Tool::Tolerance(v)});
  }
  for (int i = 1; i <= idx.edges.Extent(); ++i) {
    const TopoDS_Edge &e = TopoDS::Edge(idx.edges.FindKey(i));
    TopoDS_Vertex a, b;
    TopExp::Vertices(TopoDS::Edge(e.Oriented(TopAbs_FORWARD)), a, b);
    double first = 0.0, last = 0.0;
    BRep_Tool::Range(e, first, last);
    EdgeRec rec{};
    rec.v0 = a.IsNull() ? -1 : index_of(idx.vertices, a);
    rec.v1 = b.IsNull() ? -1 : index_of(idx.vertices, b);
    rec.degenerate = BRep_Tool::Degenerated(e);
    rec.has_curve = BRep_Tool::IsGeometric(e);
    rec.first = first;
    rec.last = last;
    rec.tolerance = BRep_Tool::Tolerance(e);
    out.edges.push_back(rec);
  }
  for (int i = 1; i <= idx.faces.Extent(); ++i) {
    const TopoDS_Face &f = TopoDS::Face(idx.faces.FindKey(i));
    FaceRec rec{};
    const TCollection_AsciiString *name = idx.names.Seek(f);
    rec.has_name = name != nullptr;
    rec.name = name ? rust::String(name->ToCString()) : rust::String();
    rec.surface_kind = surface_kind(f);
    rec.reversed = f.Orientation() == TopAbs_REVERSED;
    TopoDS_Face fwd = TopoDS::Face(f.Oriented(TopAbs_FORWARD));
    BRepTools::UVBounds(fwd, rec.u0, rec.u1, rec.v0, rec.v1);
    Handle(Geom_Surface) s = BRep_Tool::Surface(fwd);
    rec.u_periodic = s->IsUPeriodic();
    rec.v_periodic = s->IsVPeriodic();
    rec.u_period = rec.u_periodic ? s->UPeriod() : 0.0;
    rec.v_period = rec.v_periodic ? s->VPeriod() : 0.0;
    rec.tolerance = BRep_Tool::Tolerance(f);
    out.faces.push_back(rec);
    auto loops = face_loops(f);
    for (size_t l = 0; l < loops.size(); ++l) {
      for (const TopoDS_Shape &es : loops[l]) {
        const TopoDS_Edge &e = TopoDS::Edge(es);
        UseRec u{};
        u.face = i - 1;
        u.loop_index = static_cast<int32_t>(l);
        u.edge = index_of(idx.edges, e);
        u.reversed = e.Orientation() == TopAbs_REVERSED;
        u.seam = BRep_Tool::IsClosed(e, fwd);
        out.uses.push_back(u);
      }
    }
  }
  for (int i = 1; i <= idx.shells.Extent(); ++i) {
    if (!idx.shells.FindKey(i).Closed()) {
      out.shells_flagged_open.push_back(i - 1);
    }
    for (TopoDS_Iterator it(idx.shells.FindKey(i)); it.More(); it.Next()) {
      if (it.Value().ShapeType() != TopAbs_FACE) {
        continue;
      }
      ShellFaceRec r{};
      r.shell = i - 1;
      r.face = index_of(idx.faces, it.Value());
      r.reversed = it.Value().Orientation() == TopAbs_REVERSED;
      out.shell_faces.push_back(r);
    }
  }
  out.shell_count = idx.shells.Extent();
  for (int i = 1; i <= idx.solids.Extent(); ++i) {
    const TopoDS_Shape &s = idx.solids.FindKey(i);
    SolidRec rec{};
    const TCollection_AsciiString *name = idx.names.Seek(s);
    rec.has_name = name != nullptr;
    rec.name = name ? rust::String(name->ToCString()) : rust::String();
    out.solids.push_back(rec);
    for (TopoDS_Iterator it(s); it.More(); it.Next()) {
      if (it.Value().ShapeType() == TopAbs_SHELL) {
        out.solid_shells.push_back(SolidShellRec{i - 1, index_of(idx.shells, it.Value())});
      }
    }
  }
}

} // namespace tfo
