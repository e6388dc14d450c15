// A flow domain around a body: a box or a sphere (or their half on a symmetry plane) with the
// body's solids cut out. The faces of the result are named for what they came from: the outer
// solid's faces "farfield", its face on the symmetry plane "symmetry", the body's faces keep
// their own names (those without are named for their solid when the body has several, else
// "body": one wall marker a solver setup can name).
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopTools_ListOfShape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pnt.hxx>

#include <cmath>

namespace tfo {

namespace {

// Every vertex of `face` within `tol` of the plane coord[axis] = plane.
bool on_plane(const TopoDS_Shape &face, int axis, double plane, double tol) {
  bool any = false;
  for (TopExp_Explorer v(face, TopAbs_VERTEX); v.More(); v.Next()) {
    gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(v.Current()));
    if (std::abs(p.Coord(axis + 1) - plane) > tol) {
      return false;
    }
    any = true;
  }
  return any;
}

// Name what `from` became in the cut's result.
void carry(BRepAlgoAPI_Cut &cut, const TopoDS_Shape &from, const TCollection_AsciiString &name,
           ShapeIndex &out) {
  if (out.faces.Contains(from)) {
    out.names.Bind(from, name);
    return;
  }
  for (TopTools_ListOfShape::Iterator m(cut.Modified(from)); m.More(); m.Next()) {
    if (out.faces.Contains(m.Value()) && !out.names.IsBound(m.Value())) {
      out.names.Bind(m.Value(), name);
    }
  }
}

} // namespace

std::unique_ptr<ShapeIndex> farfield_domain(const ShapeIndex &body, int kind,
                                            rust::Slice<const double> centre,
                                            rust::Slice<const double> half, int axis, double plane,
                                            int side, double fuzzy) {
  if (centre.size() != 3 || half.size() != 3) {
    throw std::runtime_error("farfield_domain: centre and half extents need 3 values each");
  }
  const gp_Pnt c(centre[0], centre[1], centre[2]);
  TopoDS_Shape outer;
  if (kind == 0) {
    gp_Pnt lo(c.X() - half[0], c.Y() - half[1], c.Z() - half[2]);
    gp_Pnt hi(c.X() + half[0], c.Y() + half[1], c.Z() + half[2]);
    if (axis >= 0) {
      (side > 0 ? lo : hi).SetCoord(axis + 1, plane);
    }
    outer = BRepPrimAPI_MakeBox(lo, hi).Shape();
  } else if (axis < 0) {
    outer = BRepPrimAPI_MakeSphere(c, half[0]).Shape();
  } else {
    // The hemisphere on the kept side: latitudes 0..90° about the plane's normal, centred on
    // the plane.
    gp_Pnt on(c);
    on.SetCoord(axis + 1, plane);
    gp_Dir normal(axis == 0 ? 1 : 0, axis == 1 ? 1 : 0, axis == 2 ? 1 : 0);
    if (side < 0) {
      normal.Reverse();
    }
    outer = BRepPrimAPI_MakeSphere(gp_Ax2(on, normal), half[0], 0.0, M_PI / 2).Shape();
  }
  BRep_Builder builder;
  TopoDS_Compound tools;
  builder.MakeCompound(tools);
  for (int i = 1; i <= body.solids.Extent(); ++i) {
    builder.Add(tools, body.solids(i));
  }
  TopTools_ListOfShape arguments, cutters;
  arguments.Append(outer);
  cutters.Append(tools);
  BRepAlgoAPI_Cut cut;
  cut.SetArguments(arguments);
  cut.SetTools(cutters);
  cut.SetRunParallel(false);
  cut.SetNonDestructive(true);
  if (fuzzy > 0.0) {
    cut.SetFuzzyValue(fuzzy);
  }
  cut.Build();
  if (cut.HasErrors() || !cut.IsDone()) {
    throw std::runtime_error("cutting the body out of the far-field solid failed");
  }
  auto out = std::make_unique<ShapeIndex>(cut.Shape());
  const double tol = std::max(fuzzy, 1e-7 * half[0]);
  for (TopExp_Explorer f(outer, TopAbs_FACE); f.More(); f.Next()) {
    bool symmetry = axis >= 0 && on_plane(f.Current(), axis, plane, tol);
    carry(cut, f.Current(), symmetry ? "symmetry" : "farfield", *out);
  }
  // A face without a name of its own takes its solid's when the body has several (a wing and a
  // fuselage: each a wall marker and a refinement source of its own), else "body".
  const bool by_solid = body.solids.Extent() > 1;
  for (int i = 1; i <= body.solids.Extent(); ++i) {
    const TopoDS_Shape &solid = body.solids(i);
    const TCollection_AsciiString fallback =
        by_solid && body.names.IsBound(solid) ? body.names(solid) : "body";
    for (TopExp_Explorer f(solid, TopAbs_FACE); f.More(); f.Next()) {
      const TopoDS_Shape &face = f.Current();
      carry(cut, face, body.names.IsBound(face) ? body.names(face) : fallback, *out);
    }
  }
  return out;
}

} // namespace tfo
