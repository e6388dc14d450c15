//! A `tetrafoil serve` for tests: the binary on a free loopback port with its own data
//! folder, waited for until `/healthz` answers, killed (SIGKILL) when dropped.

use std::net::TcpListener;
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::time::{Duration, Instant};

pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder under the target directory.
pub fn scratch(name: &str) -> PathBuf {
    let dir = root()
        .join("target/test-service")
        .join(format!("{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// A running `tetrafoil serve`; killed (SIGKILL) when dropped.
pub struct Server {
    child: Child,
    pub port: u16,
    pub data: PathBuf,
    args: Vec<String>,
}

pub fn free_port() -> u16 {
    let l = TcpListener::bind("127.0.0.1:0").expect("a free port");
    l.local_addr().expect("address").port()
}

impl Server {
    pub fn start(data: &Path, args: &[&str]) -> Server {
        Self::start_on(
            data,
            free_port(),
            args.iter().map(|s| s.to_string()).collect(),
        )
    }

    pub fn start_on(data: &Path, port: u16, args: Vec<String>) -> Server {
        let log = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(data.with_extension("log"))
            .expect("server log");
        let child = super::occt::tetrafoil()
            .arg("serve")
            .arg("--data")
            .arg(data)
            .arg("--listen")
            .arg(format!("127.0.0.1:{port}"))
            .args(&args)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(log)
            .spawn()
            .expect("starting tetrafoil serve");
        let server = Server {
            child,
            port,
            data: data.to_path_buf(),
            args,
        };
        let start = Instant::now();
        while ureq::get(&server.url("/healthz")).call().is_err() {
            assert!(
                start.elapsed() < Duration::from_secs(20),
                "the server did not come up"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
        server
    }

    pub fn url(&self, path: &str) -> String {
        format!("http://127.0.0.1:{}{path}", self.port)
    }

    /// SIGKILL, then the same server again on the same data and port.
    pub fn kill_and_restart(mut self) -> Server {
        self.child.kill().expect("kill -9");
        self.child.wait().expect("reaped");
        let (data, port, args) = (self.data.clone(), self.port, self.args.clone());
        drop(self);
        Self::start_on(&data, port, args)
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
