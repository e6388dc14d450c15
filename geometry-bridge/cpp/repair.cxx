// Sewing loose faces into shells (and closed shells into solids) and ShapeFix healing.
// Names are carried to the modified sub-shapes so boundary markers survive repair.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ShapeBuild_ReShape.hxx>
#include <ShapeFix_Shape.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>

#include <vector>

namespace tfo {

std::unique_ptr<ShapeIndex> sew_shape(const ShapeIndex &idx, double tolerance, SewStats &stats) {
  BRepBuilderAPI_Sewing sewing(tolerance);
  sewing.Add(idx.shape);
  sewing.Perform();
  TopoDS_Shape sewn = sewing.SewedShape();
  stats.free_edges = sewing.NbFreeEdges();
  stats.multiple_edges = sewing.NbMultipleEdges();
  stats.degenerated = sewing.NbDegeneratedShapes();

  // Closed shells become solids (ShapeFix_Solid orients them outward); open shells and
  // loose faces stay as they are.
  BRep_Builder builder;
  TopoDS_Compound result;
  builder.MakeCompound(result);
  int items = 0;
  TopoDS_Shape last;
  auto add = [&](const TopoDS_Shape &s) {
    builder.Add(result, s);
    last = s;
    ++items;
  };
  // A loose face that closes on itself (an untrimmed sphere or torus: only seam and degenerate
  // edges) is a closed shell of one face; sewing leaves it a face, so wrap it first.
  std::vector<TopoDS_Shell> shells;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    shells.push_back(TopoDS::Shell(ex.Current()));
  }
  std::vector<TopoDS_Shape> loose;
  for (TopExp_Explorer ex(sewn, TopAbs_FACE, TopAbs_SHELL); ex.More(); ex.Next()) {
    TopoDS_Shell one;
    builder.MakeShell(one);
    builder.Add(one, ex.Current());
    if (BRep_Tool::IsClosed(one)) {
      one.Closed(true);
      shells.push_back(one);
    } else {
      loose.push_back(ex.Current());
    }
  }
  for (const TopoDS_Shell &shell : shells) {
    if (BRep_Tool::IsClosed(shell)) {
      ++stats.closed_shells;
      BRepBuilderAPI_MakeSolid make(shell);
      if (make.IsDone()) {
        ShapeFix_Solid fix;
        TopoDS_Solid solid = fix.SolidFromShell(shell);
        add(solid.IsNull() ? make.Solid() : solid);
        ++stats.solids_made;
        continue;
      }
    } else {
      ++stats.open_shells;
    }
    add(shell);
  }
  for (const TopoDS_Shape &face : loose) {
    add(face);
  }
  auto out = std::make_unique<ShapeIndex>(items == 1 ? last : TopoDS_Shape(result));
  // SolidFromShell may rebuild faces; names go to sub-shapes that are still the same.
  for (NameMap::Iterator it(idx.names); it.More(); it.Next()) {
    TopoDS_Shape s = it.Key();
    if (sewing.IsModified(s)) {
      s = sewing.Modified(s);
    }
    if (out->faces.Contains(s) || out->solids.Contains(s)) {
      out->names.Bind(s, it.Value());
    }
  }
  return out;
}

std::unique_ptr<ShapeIndex> heal_shape(const ShapeIndex &idx, double tolerance) {
  ShapeFix_Shape fix(idx.shape);
  fix.SetPrecision(tolerance);
  fix.SetMaxTolerance(tolerance * 100.0);
  fix.Perform();
  auto out = std::make_unique<ShapeIndex>(fix.Shape());
  Handle(ShapeBuild_ReShape) ctx = fix.Context();
  for (NameMap::Iterator it(idx.names); it.More(); it.Next()) {
    TopoDS_Shape s = ctx.IsNull() ? it.Key() : ctx->Apply(it.Key());
    if (!s.IsNull() && (out->faces.Contains(s) || out->solids.Contains(s))) {
      out->names.Bind(s, it.Value());
    }
  }
  return out;
}

} // namespace tfo
