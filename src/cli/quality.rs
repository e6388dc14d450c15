use crate::io::vtk;
use crate::mesh::quality;
use clap::Args;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub struct QualityArgs {
    /// Mesh file (.vtu or .vtk as tetrafoil writes them).
    pub mesh: PathBuf,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn run(a: QualityArgs) -> anyhow::Result<()> {
    let m = vtk::read(&a.mesh)?;
    let r = quality::report(&m.points, &m.cells);
    if a.json {
        println!("{}", serde_json::to_string_pretty(&r)?);
        return Ok(());
    }
    println!("{}: {} points", a.mesh.display(), r.points);
    let line = |name: &str, s: &quality::Stats| {
        if s.count > 0 {
            println!(
                "  {name:<20} n {:>9}  min {:>10.4}  mean {:>10.4}  max {:>10.4}",
                s.count, s.min, s.mean, s.max
            );
        }
    };
    line("segment length", &r.segment_length);
    line("triangle min angle", &r.triangle_min_angle);
    line("tet dihedral", &r.tet_dihedral);
    line("tet radius ratio", &r.tet_radius_ratio);
    if r.tet_dihedral.count > 0 {
        println!("  inverted tets {}", r.inverted_tets);
    }
    if r.prisms + r.pyramids > 0 {
        println!(
            "  prisms {}, pyramids {} (counted, not measured)",
            r.prisms, r.pyramids
        );
    }
    Ok(())
}
