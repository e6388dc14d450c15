// Sewing loose faces into shells (and closed shells into solids) and ShapeFix healing.
// Names are carried to the modified sub-shapes so boundary markers survive repair.
#include "tetrafoil-occt/cpp/shim.hxx"
#include "tetrafoil-occt/src/ffi.rs.h"

#include <BRepAlgoAPI_BuilderAlgo.hxx>
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
#include <TopTools_ListOfShape.hxx>

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

std::unique_ptr<ShapeIndex> fuse_solids(const ShapeIndex &idx, double fuzzy) {
  // General fuse (BOPAlgo_Builder): every solid is split where it touches or overlaps another,
  // and the pieces share the faces along their contacts, so the mesher sees one interface
  // instead of two coincident, unrelated surfaces.
  TopTools_ListOfShape arguments;
  for (int i = 1; i <= idx.solids.Extent(); ++i) {
    arguments.Append(idx.solids(i));
  }
  BRepAlgoAPI_BuilderAlgo fuse;
  fuse.SetArguments(arguments);
  fuse.SetRunParallel(false);
  fuse.SetNonDestructive(true);
  if (fuzzy > 0.0) {
    fuse.SetFuzzyValue(fuzzy);
  }
  fuse.Build();
  if (fuse.HasErrors() || !fuse.IsDone()) {
    throw std::runtime_error("the general fuse of the solids failed");
  }
  auto out = std::make_unique<ShapeIndex>(fuse.Shape());
  // Names go to what each named solid or face became (all its pieces keep the name).
  for (NameMap::Iterator it(idx.names); it.More(); it.Next()) {
    const TopoDS_Shape &s = it.Key();
    if (out->faces.Contains(s) || out->solids.Contains(s)) {
      out->names.Bind(s, it.Value());
      continue;
    }
    for (TopTools_ListOfShape::Iterator m(fuse.Modified(s)); m.More(); m.Next()) {
      if ((out->faces.Contains(m.Value()) || out->solids.Contains(m.Value())) &&
          !out->names.IsBound(m.Value())) {
        out->names.Bind(m.Value(), it.Value());
      }
    }
  }
  return out;
}

std::unique_ptr<ShapeIndex> solids_only(const ShapeIndex &idx) {
  // A compound of the solids alone: surfaces and open shells lying beside them in the file
  // (construction geometry, SHELL_BASED_SURFACE_MODEL items) are left out.
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (int i = 1; i <= idx.solids.Extent(); ++i) {
    builder.Add(compound, idx.solids(i));
  }
  auto out = std::make_unique<ShapeIndex>(compound);
  for (NameMap::Iterator it(idx.names); it.More(); it.Next()) {
    if (out->faces.Contains(it.Key()) || out->solids.Contains(it.Key())) {
      out->names.Bind(it.Key(), it.Value());
    }
  }
  return out;
}

} // namespace tfo
