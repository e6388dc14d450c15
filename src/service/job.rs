//! A job as the API shows it: its state, the stage running and how far it is, timings, the
//! report of a finished run and the error of a failed one; and the options it was sent with.

use crate::io::MeshFormat;
use serde::{Deserialize, Serialize};

/// Where a job is. `Queued` and `Running` are the live states; the other three are final.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum State {
    Queued,
    Running,
    Done,
    Failed,
    Cancelled,
}

impl State {
    pub const ALL: [State; 5] = [
        State::Queued,
        State::Running,
        State::Done,
        State::Failed,
        State::Cancelled,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            State::Queued => "queued",
            State::Running => "running",
            State::Done => "done",
            State::Failed => "failed",
            State::Cancelled => "cancelled",
        }
    }

    pub fn parse(s: &str) -> Option<State> {
        State::ALL.into_iter().find(|x| x.as_str() == s)
    }

    pub fn is_final(self) -> bool {
        matches!(self, State::Done | State::Failed | State::Cancelled)
    }
}

/// What a submission asked for, stored with the job (as JSON) and read back by the worker.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Options {
    /// The input the worker loads: `case.toml` or `geometry.<ext>` under the job's input
    /// folder (a name the server chose, never the client's).
    pub input: String,
    /// Background spacing override.
    pub size: Option<f64>,
    /// Result formats, by their `--format` names.
    pub formats: Vec<String>,
    /// Threads for this job (at most the server's `--threads-per-job`).
    pub threads: usize,
    /// One more directional refinement stage, after the case's own `[[refine]]` stages.
    #[serde(default)]
    pub refine: Option<Refine>,
}

/// The submission's refinement stage (as `tetrafoil mesh --refine-faces …`).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Refine {
    pub faces: Vec<String>,
    pub curves: Vec<String>,
    pub first: Option<f64>,
    /// The first layer from a y⁺ target (with `reynolds` and `chord`) instead of `first`.
    #[serde(default)]
    pub yplus: Option<f64>,
    #[serde(default)]
    pub reynolds: Option<f64>,
    #[serde(default)]
    pub chord: Option<f64>,
    pub growth: f64,
    pub constant: usize,
    pub thickness: Option<f64>,
}

impl Options {
    /// The formats as writer formats; names were checked at submission.
    pub fn mesh_formats(&self) -> Vec<(String, MeshFormat)> {
        self.formats
            .iter()
            .filter_map(|n| parse_format(n).map(|f| (n.clone(), f)))
            .collect()
    }
}

/// A format by its `--format` name (`su2`, `msh`, `msh22`, `mesh`, `vtu`, `vtu-binary`, `vtk`,
/// `stl`).
pub fn parse_format(name: &str) -> Option<MeshFormat> {
    <MeshFormat as clap::ValueEnum>::from_str(name, false).ok()
}

/// Every format name the writers know, for error messages.
pub fn format_names() -> Vec<String> {
    <MeshFormat as clap::ValueEnum>::value_variants()
        .iter()
        .filter_map(|f| clap::ValueEnum::to_possible_value(f).map(|v| v.get_name().to_string()))
        .collect()
}

/// How far the running stage is.
#[derive(Clone, Debug, Serialize)]
pub struct StageProgress {
    pub stage: Option<String>,
    pub done: u64,
    pub total: u64,
    /// `done / total` in [0, 1] (0 without a count).
    pub fraction: f64,
}

/// One finished stage of a run.
#[derive(Clone, Debug, Serialize)]
pub struct Timing {
    pub stage: String,
    pub seconds: f64,
}

/// One job as `GET /v1/jobs/{id}` answers it.
#[derive(Clone, Debug, Serialize)]
pub struct Job {
    pub id: String,
    #[serde(skip)]
    pub owner: String,
    pub state: State,
    pub progress: StageProgress,
    /// Seconds since the Unix epoch.
    pub created: f64,
    pub started: Option<f64>,
    pub finished: Option<f64>,
    /// The finished stages of the current (or last) run, in order.
    pub timings: Vec<Timing>,
    pub options: Options,
    /// Runs started: more than one after a restart re-ran the job.
    pub attempts: u32,
    pub report: Option<serde_json::Value>,
    pub error: Option<String>,
    /// The result formats that can be downloaded (done jobs).
    pub results: Vec<String>,
}
