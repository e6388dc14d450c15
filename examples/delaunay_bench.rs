//! Benchmark driver for the Delaunay kernel (run by `benches/delaunay-peers.sh`).
//!
//! ```text
//! delaunay_bench gen <uniform|lattice|sphere> <n> <out.xyz> [seed]   write a point set
//! delaunay_bench node <in.xyz> <out.node>                          convert for TetGen
//! delaunay_bench run <in.xyz> [--threads N] [--check]              triangulate and time
//! ```
//! Point files are plain text, one `x y z` per line, written with Rust's shortest
//! round-trip formatting so every tool reads bit-identical coordinates.

use std::io::{BufRead, BufWriter, Write};
use std::time::Instant;

use tetrafoil::volume::delaunay::Delaunay;

fn read_xyz(path: &str) -> Vec<[f64; 3]> {
    let f = std::fs::File::open(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    std::io::BufReader::new(f)
        .lines()
        .map_while(Result::ok)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let mut it = l
                .split_whitespace()
                .map(|t| t.parse::<f64>().expect("number"));
            [it.next().unwrap(), it.next().unwrap(), it.next().unwrap()]
        })
        .collect()
}

/// CPU seconds used by this process so far (all threads; Linux `/proc`, else 0): beside the
/// wall time it shows how much of a run the machine's other load took.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')').map(|x| x.1).unwrap_or("");
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|x| x.parse().ok())
        .collect();
    f.iter().sum::<f64>() / 100.0
}

struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn generate(kind: &str, n: usize, seed: u64) -> Vec<[f64; 3]> {
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    match kind {
        "uniform" => (0..n).map(|_| [r.f(), r.f(), r.f()]).collect(),
        "lattice" => {
            let m = (n as f64).cbrt().round() as usize;
            let mut v = Vec::with_capacity(m * m * m);
            for i in 0..m {
                for j in 0..m {
                    for k in 0..m {
                        v.push([i as f64, j as f64, k as f64]);
                    }
                }
            }
            v
        }
        "sphere" => (0..n)
            .map(|_| loop {
                let q = [2.0 * r.f() - 1.0, 2.0 * r.f() - 1.0, 2.0 * r.f() - 1.0];
                let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
                if l > 0.1 && l <= 1.0 {
                    break [q[0] / l, q[1] / l, q[2] / l];
                }
            })
            .collect(),
        other => panic!("unknown point set kind {other}"),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("gen") => {
            let n: usize = args[3].parse().expect("n");
            let seed = args.get(5).map(|s| s.parse().expect("seed")).unwrap_or(1);
            let pts = generate(&args[2], n, seed);
            let mut w = BufWriter::new(std::fs::File::create(&args[4]).expect("create"));
            for p in &pts {
                writeln!(w, "{} {} {}", p[0], p[1], p[2]).unwrap();
            }
        }
        Some("node") => {
            let pts = read_xyz(&args[2]);
            let mut w = BufWriter::new(std::fs::File::create(&args[3]).expect("create"));
            writeln!(w, "{} 3 0 0", pts.len()).unwrap();
            for (i, p) in pts.iter().enumerate() {
                writeln!(w, "{} {} {} {}", i + 1, p[0], p[1], p[2]).unwrap();
            }
        }
        Some("run") => {
            let pts = read_xyz(&args[2]);
            let mut threads = 1usize;
            let mut check = false;
            let mut i = 3;
            while i < args.len() {
                match args[i].as_str() {
                    "--threads" => {
                        threads = args[i + 1].parse().expect("threads");
                        i += 1;
                    }
                    "--check" => check = true,
                    other => panic!("unknown option {other}"),
                }
                i += 1;
            }
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("pool");
            let c0 = cpu_seconds();
            let t0 = Instant::now();
            let d = pool
                .install(|| Delaunay::from_vec(pts))
                .expect("triangulation");
            let secs = t0.elapsed().as_secs_f64();
            let cpu = cpu_seconds() - c0;
            let tets = d.num_tets();
            let bytes = d.memory_bytes() as f64 / tets as f64;
            print!(
                "tets {tets} seconds {secs:.4} cpu_seconds {cpu:.2} threads {threads} \
                 bytes_per_tet {bytes:.1} hull {} duplicates {}",
                d.num_hull_faces(),
                d.duplicates().len()
            );
            if check {
                let t1 = Instant::now();
                match d.check() {
                    Ok(_) => print!(" check ok ({:.2} s)", t1.elapsed().as_secs_f64()),
                    Err(e) => print!(" check FAILED: {e}"),
                }
            }
            println!();
        }
        _ => {
            eprintln!("usage: delaunay_bench gen|node|run ... (see source)");
            std::process::exit(2);
        }
    }
}
