// Geometry handles: deep copies of a face's surface, an edge's curve and an edge use's pcurve,
// so that each Rust handle owns C++ state nobody else touches.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <GProp_GProps.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_IntCS.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ElementarySurface.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Curve.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec2d.hxx>

#include <stdexcept>

namespace tfo {

namespace {

const TopoDS_Shape &checked(const TopTools_IndexedMapOfShape &m, int32_t i, const char *what) {
  if (i < 0 || i >= m.Extent()) {
    throw std::out_of_range(std::string(what) + " index out of range");
  }
  return m.FindKey(i + 1);
}

void put(rust::Slice<double> out, size_t at, const gp_XYZ &v) {
  out[at] = v.X();
  out[at + 1] = v.Y();
  out[at + 2] = v.Z();
}

} // namespace

SurfaceGeom::SurfaceGeom(const Handle(Geom_Surface) &s)
    : surface(s), analysis(s), u0(0), u1(0), v0(0), v1(0) {}

std::unique_ptr<SurfaceGeom> face_surface(const ShapeIndex &idx, int32_t face) {
  TopoDS_Face f = TopoDS::Face(checked(idx.faces, face, "face").Oriented(TopAbs_FORWARD));
  TopLoc_Location loc;
  const Handle(Geom_Surface) &s = BRep_Tool::Surface(f, loc);
  if (s.IsNull()) {
    throw std::runtime_error("face has no surface");
  }
  Handle(Geom_Surface) copy = Handle(Geom_Surface)::DownCast(s->Copy());
  if (!loc.IsIdentity()) {
    copy->Transform(loc.Transformation());
  }
  auto g = std::make_unique<SurfaceGeom>(copy);
  BRepTools::UVBounds(f, g->u0, g->u1, g->v0, g->v1);
  return g;
}

std::unique_ptr<SurfaceGeom> surface_clone(const SurfaceGeom &g) {
  auto c = std::make_unique<SurfaceGeom>(Handle(Geom_Surface)::DownCast(g.surface->Copy()));
  c->u0 = g.u0;
  c->u1 = g.u1;
  c->v0 = g.v0;
  c->v1 = g.v1;
  return c;
}

void surface_info(const SurfaceGeom &g, rust::Slice<double> out) {
  out[0] = g.u0;
  out[1] = g.u1;
  out[2] = g.v0;
  out[3] = g.v1;
  out[4] = g.surface->IsUPeriodic() ? g.surface->UPeriod() : 0.0;
  out[5] = g.surface->IsVPeriodic() ? g.surface->VPeriod() : 0.0;
  out[6] = g.surface->IsKind(STANDARD_TYPE(Geom_ElementarySurface)) ? 1.0 : 0.0;
}

void surface_d2(const SurfaceGeom &g, double u, double v, rust::Slice<double> out) {
  gp_Pnt p;
  gp_Vec du, dv, duu, dvv, duv;
  if (!g.adaptor) {
    g.adaptor = std::make_unique<GeomAdaptor_Surface>(g.surface);
  }
  g.adaptor->D2(u, v, p, du, dv, duu, dvv, duv);
  put(out, 0, p.XYZ());
  put(out, 3, du.XYZ());
  put(out, 6, dv.XYZ());
  put(out, 9, duu.XYZ());
  put(out, 12, duv.XYZ());
  put(out, 15, dvv.XYZ());
}

bool surface_project(SurfaceGeom &g, rust::Slice<const double> p, bool has_hint,
                     rust::Slice<double> out) {
  gp_Pnt point(p[0], p[1], p[2]);
  double preci = Precision::Confusion();
  gp_Pnt2d uv = has_hint ? g.analysis.NextValueOfUV(gp_Pnt2d(p[3], p[4]), point, preci)
                         : g.analysis.ValueOfUV(point, preci);
  out[0] = uv.X();
  out[1] = uv.Y();
  out[2] = g.analysis.Gap();
  return true;
}

rust::Vec<double> surface_intersect_circle(const SurfaceGeom &g, rust::Slice<const double> c) {
  gp_Ax2 axes(gp_Pnt(c[0], c[1], c[2]), gp_Dir(c[3], c[4], c[5]), gp_Dir(c[6], c[7], c[8]));
  Handle(Geom_Circle) circle = new Geom_Circle(axes, c[9]);
  GeomAPI_IntCS inter(circle, g.surface);
  rust::Vec<double> out;
  if (!inter.IsDone()) {
    throw std::runtime_error("circle-surface intersection failed");
  }
  for (Standard_Integer i = 1; i <= inter.NbPoints(); ++i) {
    double u = 0, v = 0, w = 0;
    inter.Parameters(i, u, v, w);
    gp_Pnt q = inter.Point(i);
    for (double x : {u, v, w, q.X(), q.Y(), q.Z()}) {
      out.push_back(x);
    }
  }
  return out;
}

std::unique_ptr<CurveGeom> edge_curve(const ShapeIndex &idx, int32_t edge) {
  const TopoDS_Edge &e = TopoDS::Edge(checked(idx.edges, edge, "edge"));
  TopLoc_Location loc;
  double first = 0, last = 0;
  Handle(Geom_Curve) c = BRep_Tool::Curve(e, loc, first, last);
  if (c.IsNull()) {
    return nullptr;
  }
  auto g = std::make_unique<CurveGeom>();
  g->curve = Handle(Geom_Curve)::DownCast(c->Copy());
  if (!loc.IsIdentity()) {
    g->curve->Transform(loc.Transformation());
  }
  g->first = first;
  g->last = last;
  return g;
}

std::unique_ptr<CurveGeom> curve_clone(const CurveGeom &g) {
  auto c = std::make_unique<CurveGeom>();
  c->curve = Handle(Geom_Curve)::DownCast(g.curve->Copy());
  c->first = g.first;
  c->last = g.last;
  return c;
}

void curve_range(const CurveGeom &g, rust::Slice<double> out) {
  out[0] = g.first;
  out[1] = g.last;
  out[2] = g.curve->IsPeriodic() ? g.curve->Period() : 0.0;
}

void curve_d2(const CurveGeom &g, double t, rust::Slice<double> out) {
  gp_Pnt p;
  gp_Vec d1, d2;
  if (!g.adaptor) {
    g.adaptor = std::make_unique<GeomAdaptor_Curve>(g.curve);
  }
  g.adaptor->D2(t, p, d1, d2);
  put(out, 0, p.XYZ());
  put(out, 3, d1.XYZ());
  put(out, 6, d2.XYZ());
}

bool curve_project(const CurveGeom &g, rust::Slice<const double> p, bool has_hint, double hint,
                   rust::Slice<double> out) {
  ShapeAnalysis_Curve sac;
  gp_Pnt point(p[0], p[1], p[2]);
  gp_Pnt proj;
  double param = 0;
  double preci = Precision::Confusion();
  double dist =
      has_hint ? sac.NextProject(hint, g.curve, point, preci, proj, param, g.first, g.last, false)
               : sac.Project(g.curve, point, preci, proj, param, g.first, g.last, false);
  out[0] = param;
  out[1] = dist;
  return true;
}

std::unique_ptr<PcurveGeom> use_pcurve(const ShapeIndex &idx, int32_t face, int32_t loop,
                                       int32_t use) {
  TopoDS_Face f = TopoDS::Face(checked(idx.faces, face, "face").Oriented(TopAbs_FORWARD));
  auto loops = face_loops(f);
  if (loop < 0 || static_cast<size_t>(loop) >= loops.size() || use < 0 ||
      static_cast<size_t>(use) >= loops[loop].size()) {
    throw std::out_of_range("edge use index out of range");
  }
  // The use's oriented edge selects which of a seam's two pcurves is returned.
  const TopoDS_Edge &e = TopoDS::Edge(loops[loop][use]);
  double first = 0, last = 0;
  Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(e, f, first, last);
  if (c.IsNull()) {
    throw std::runtime_error("edge use has no pcurve on its face");
  }
  auto g = std::make_unique<PcurveGeom>();
  g->curve = Handle(Geom2d_Curve)::DownCast(c->Copy());
  g->first = first;
  g->last = last;
  return g;
}

std::unique_ptr<PcurveGeom> pcurve_clone(const PcurveGeom &g) {
  auto c = std::make_unique<PcurveGeom>();
  c->curve = Handle(Geom2d_Curve)::DownCast(g.curve->Copy());
  c->first = g.first;
  c->last = g.last;
  return c;
}

void pcurve_range(const PcurveGeom &g, rust::Slice<double> out) {
  out[0] = g.first;
  out[1] = g.last;
}

void pcurve_d2(const PcurveGeom &g, double t, rust::Slice<double> out) {
  gp_Pnt2d p;
  gp_Vec2d d1, d2;
  if (!g.adaptor) {
    g.adaptor = std::make_unique<Geom2dAdaptor_Curve>(g.curve);
  }
  g.adaptor->D2(t, p, d1, d2);
  out[0] = p.X();
  out[1] = p.Y();
  out[2] = d1.X();
  out[3] = d1.Y();
  out[4] = d2.X();
  out[5] = d2.Y();
}

double adaptive_measure(const ShapeIndex &idx, int32_t kind, int32_t i, double eps) {
  TopoDS_Shape s = *sub_shape(idx, kind, i);
  GProp_GProps props;
  // The adaptive integrators: the fixed-order default is off by percents on faces bounded
  // by dense B-spline pcurves (a lofted wing's tip cap: 10 %).
  if (kind == 2) {
    BRepGProp::SurfaceProperties(s, props, eps);
  } else {
    BRepGProp::VolumeProperties(s, props, eps);
  }
  return props.Mass();
}

} // namespace tfo
