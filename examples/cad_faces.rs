//! Per-face comparison of the imported CAD model with OpenCASCADE: loops (edge uses with their
//! (u,v) end points), the root's boundary integrals (loop areas, area, flux) and BRepGProp's
//! area. Usage: cargo run --example cad_faces -- FILE [FACE...]
#[cfg(feature = "occt")]
fn main() {
    use tetrafoil::model::cad::import_cad;
    let args: Vec<String> = std::env::args().skip(1).collect();
    let cad = tetrafoil_occt::CadModel::read(&args[0]).unwrap_or_else(|e| panic!("{e}"));
    let mut model = import_cad(&cad).unwrap_or_else(|e| panic!("{e}"));
    let orient = model.orient();
    println!("orient: {:?}", orient.as_ref().err().map(|e| e.to_string()));
    let faces: Vec<usize> = if args.len() > 1 {
        args[1..].iter().map(|a| a.parse().unwrap()).collect()
    } else {
        (0..model.faces.len()).collect()
    };
    let t = cad.topology();
    for f in faces {
        let cf = &t.faces[f];
        println!(
            "face {f} {} u {:?} v {:?} periods {:?} {:?} occt area {:.6e}",
            cf.surface_kind,
            cf.u_range,
            cf.v_range,
            cf.u_period,
            cf.v_period,
            cad.face_area(f).unwrap()
        );
        println!("  root integrals {:?}", model.face_integrals(f));
        for (l, lp) in model.faces[f].loops.iter().enumerate() {
            for u in &lp.uses {
                let e = &model.edges[u.edge];
                let pc = u.pcurve.as_ref().unwrap();
                println!(
                    "  loop {l} edge {} rev {} degen {} range {:?} pc range {:?} uv {:?} -> {:?}",
                    u.edge,
                    u.reversed,
                    e.is_degenerate(),
                    e.range,
                    pc.range(),
                    pc.point(e.range.0),
                    pc.point(e.range.1)
                );
            }
        }
    }
}

#[cfg(not(feature = "occt"))]
fn main() {
    eprintln!("needs the occt feature");
}
