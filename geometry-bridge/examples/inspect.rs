//! Prints a CAD file's faces (kind, ranges, periods, loops, area) and solids (volume, name).
//! Usage: cargo run -p tetrafoil-occt --example inspect -- FILE [SEW_TOLERANCE]
use tetrafoil_occt::CadModel;

fn main() {
    let path = std::env::args().nth(1).expect("usage: inspect FILE");
    let model = match CadModel::read(&path) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let model = match std::env::args()
        .nth(2)
        .map(|t| t.parse::<f64>().expect("tolerance"))
    {
        Some(tol) => {
            let (sewn, report) = model.sew(tol).expect("sewing");
            println!("{report:?}");
            sewn
        }
        None => model,
    };
    let t = model.topology();
    println!("{:?}", t.counts());
    println!("check: {:?}", model.check_solids());
    println!("bbox {:?}", model.bounding_box());
    for (i, f) in t.faces.iter().enumerate() {
        println!(
            "face {i} {} rev={} u={:?} v={:?} per=({:?},{:?}) area={:.6} name={:?}",
            f.surface_kind,
            f.orientation_reversed,
            f.u_range,
            f.v_range,
            f.u_period,
            f.v_period,
            model.face_area(i).unwrap_or(f64::NAN),
            f.name
        );
        for l in &f.loops {
            let s: Vec<String> = l
                .iter()
                .map(|u| {
                    let e = &t.edges[u.edge];
                    format!(
                        "{}{}{}{}",
                        u.edge,
                        if u.reversed { "r" } else { "" },
                        if u.seam { "s" } else { "" },
                        if e.degenerate { "d" } else { "" }
                    )
                })
                .collect();
            println!("  loop {}", s.join(" "));
        }
    }
    for (i, s) in t.solids.iter().enumerate() {
        println!("solid {i} {:?} volume={:?}", s.name, model.solid_volume(i));
    }
}
