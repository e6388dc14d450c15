//! Jobs and their events in SQLite (the bundled library, WAL mode: readers never wait for
//! the worker writing progress, and a `kill -9` loses nothing committed). One connection
//! behind a mutex: every statement here is short, and the writes are a few per second per job.

use super::job::{Job, Options, StageProgress, State, Timing};
use rusqlite::{params, Connection, OptionalExtension, Row};
use std::path::Path;
use std::sync::{Mutex, MutexGuard};

pub type Result<T> = rusqlite::Result<T>;

/// Seconds since the Unix epoch.
pub fn now() -> f64 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs_f64())
        .unwrap_or(0.0)
}

/// One stored event of a job.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Event {
    pub id: i64,
    pub at: f64,
    /// `queued`, `started`, `stage`, `stage_done`, `progress`, `requeued`, `done`, `failed`,
    /// `cancelled`.
    pub kind: String,
    pub stage: Option<String>,
    pub done: Option<u64>,
    pub total: Option<u64>,
    pub seconds: Option<f64>,
    pub message: Option<String>,
    pub attempt: u32,
}

impl Event {
    /// Whether the job ends with this event.
    pub fn is_final(&self) -> bool {
        State::parse(&self.kind).is_some_and(State::is_final)
    }
}

/// What one event says; the store adds the id, job, time and attempt.
#[derive(Clone, Debug, Default)]
pub struct NewEvent<'a> {
    pub kind: &'a str,
    pub stage: Option<&'a str>,
    pub done: Option<u64>,
    pub total: Option<u64>,
    pub seconds: Option<f64>,
    pub message: Option<&'a str>,
}

pub struct Store {
    conn: Mutex<Connection>,
}

const SCHEMA: &str = "
CREATE TABLE IF NOT EXISTS jobs (
    seq INTEGER PRIMARY KEY AUTOINCREMENT,
    id TEXT NOT NULL UNIQUE,
    owner TEXT NOT NULL,
    state TEXT NOT NULL,
    created REAL NOT NULL,
    started REAL,
    finished REAL,
    stage TEXT,
    done INTEGER NOT NULL DEFAULT 0,
    total INTEGER NOT NULL DEFAULT 0,
    options TEXT NOT NULL,
    report TEXT,
    error TEXT,
    attempts INTEGER NOT NULL DEFAULT 0,
    results TEXT NOT NULL DEFAULT '[]'
);
CREATE TABLE IF NOT EXISTS events (
    id INTEGER PRIMARY KEY AUTOINCREMENT,
    job TEXT NOT NULL,
    at REAL NOT NULL,
    kind TEXT NOT NULL,
    stage TEXT,
    done INTEGER,
    total INTEGER,
    seconds REAL,
    message TEXT,
    attempt INTEGER NOT NULL
);
CREATE INDEX IF NOT EXISTS events_by_job ON events (job, id);
";

const JOB_COLUMNS: &str = "id, owner, state, created, started, finished, stage, done, total, \
                           options, report, error, attempts, results";

impl Store {
    /// Open (or create) the database at `path`, in WAL mode.
    pub fn open(path: &Path) -> Result<Store> {
        let conn = Connection::open(path)?;
        conn.pragma_update(None, "journal_mode", "WAL")?;
        // WAL with NORMAL still survives a killed process (only a power cut can lose the
        // last commits), and spares an fsync per progress event.
        conn.pragma_update(None, "synchronous", "NORMAL")?;
        conn.busy_timeout(std::time::Duration::from_secs(5))?;
        conn.execute_batch(SCHEMA)?;
        Ok(Store {
            conn: Mutex::new(conn),
        })
    }

    fn conn(&self) -> MutexGuard<'_, Connection> {
        self.conn.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A new queued job, with its `queued` event, in one transaction.
    pub fn insert(&self, id: &str, owner: &str, options: &Options) -> Result<()> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        let json = serde_json::to_string(options).unwrap_or_default();
        tx.execute(
            "INSERT INTO jobs (id, owner, state, created, options) VALUES (?1, ?2, ?3, ?4, ?5)",
            params![id, owner, State::Queued.as_str(), now(), json],
        )?;
        insert_event(&tx, id, 0, &NewEvent::kind("queued"))?;
        tx.commit()
    }

    pub fn get(&self, id: &str) -> Result<Option<Job>> {
        let conn = self.conn();
        let sql = format!("SELECT {JOB_COLUMNS} FROM jobs WHERE id = ?1");
        let job = conn.query_row(&sql, [id], job_of_row).optional()?;
        match job {
            Some(mut job) => {
                job.timings = timings(&conn, id, job.attempts)?;
                Ok(Some(job))
            }
            None => Ok(None),
        }
    }

    /// The owner's jobs, oldest first (without timings and reports: a list stays small).
    pub fn list(&self, owner: &str) -> Result<Vec<Job>> {
        let conn = self.conn();
        let sql = format!("SELECT {JOB_COLUMNS} FROM jobs WHERE owner = ?1 ORDER BY seq");
        let mut stmt = conn.prepare(&sql)?;
        let jobs = stmt.query_map([owner], job_of_row)?;
        jobs.map(|j| {
            j.map(|mut j| {
                j.report = None;
                j
            })
        })
        .collect()
    }

    /// Take a queued job for a run: `false` if it is no longer queued (cancelled meanwhile).
    pub fn claim(&self, id: &str) -> Result<Option<u32>> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        let n = tx.execute(
            "UPDATE jobs SET state = 'running', started = ?2, attempts = attempts + 1, \
             stage = NULL, done = 0, total = 0 WHERE id = ?1 AND state = 'queued'",
            params![id, now()],
        )?;
        if n == 0 {
            return Ok(None);
        }
        let attempt: u32 = tx.query_row("SELECT attempts FROM jobs WHERE id = ?1", [id], |r| {
            r.get(0)
        })?;
        insert_event(&tx, id, attempt, &NewEvent::kind("started"))?;
        tx.commit()?;
        Ok(Some(attempt))
    }

    /// Record an event of the running attempt; a stage or progress event also moves the
    /// job's current stage and count.
    pub fn event(&self, id: &str, attempt: u32, event: &NewEvent<'_>) -> Result<()> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        insert_event(&tx, id, attempt, event)?;
        if let Some(stage) = event.stage {
            if event.kind != "stage_done" {
                tx.execute(
                    "UPDATE jobs SET stage = ?2, done = ?3, total = ?4 WHERE id = ?1",
                    params![
                        id,
                        stage,
                        event.done.unwrap_or(0) as i64,
                        event.total.unwrap_or(0) as i64
                    ],
                )?;
            }
        }
        tx.commit()
    }

    /// End a run: `state` is final; the report, error and result formats as they are.
    pub fn finish(
        &self,
        id: &str,
        attempt: u32,
        state: State,
        report: Option<&serde_json::Value>,
        error: Option<&str>,
        results: &[String],
    ) -> Result<()> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        tx.execute(
            "UPDATE jobs SET state = ?2, finished = ?3, report = ?4, error = ?5, results = ?6 \
             WHERE id = ?1",
            params![
                id,
                state.as_str(),
                now(),
                report.map(|r| r.to_string()),
                error,
                serde_json::to_string(results).unwrap_or_default()
            ],
        )?;
        let event = NewEvent {
            message: error,
            ..NewEvent::kind(state.as_str())
        };
        insert_event(&tx, id, attempt, &event)?;
        tx.commit()
    }

    /// Cancel a queued job; `false` when it was not queued.
    pub fn cancel_queued(&self, id: &str) -> Result<bool> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        let n = tx.execute(
            "UPDATE jobs SET state = 'cancelled', finished = ?2 WHERE id = ?1 AND state = 'queued'",
            params![id, now()],
        )?;
        if n > 0 {
            let attempt: u32 =
                tx.query_row("SELECT attempts FROM jobs WHERE id = ?1", [id], |r| {
                    r.get(0)
                })?;
            insert_event(&tx, id, attempt, &NewEvent::kind("cancelled"))?;
        }
        tx.commit()?;
        Ok(n > 0)
    }

    /// Forget a job and its events.
    pub fn delete(&self, id: &str) -> Result<()> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        tx.execute("DELETE FROM events WHERE job = ?1", [id])?;
        tx.execute("DELETE FROM jobs WHERE id = ?1", [id])?;
        tx.commit()
    }

    /// After a restart: jobs that were running go back to the queue (with a `requeued` event);
    /// returns every queued job, oldest first.
    pub fn recover(&self) -> Result<(Vec<String>, Vec<String>)> {
        let mut conn = self.conn();
        let tx = conn.transaction()?;
        let running: Vec<(String, u32)> = {
            let mut stmt = tx.prepare("SELECT id, attempts FROM jobs WHERE state = 'running'")?;
            let rows = stmt.query_map([], |r| Ok((r.get(0)?, r.get(1)?)))?;
            rows.collect::<Result<_>>()?
        };
        for (id, attempt) in &running {
            let event = NewEvent {
                message: Some("the server restarted during the run: run again from the start"),
                ..NewEvent::kind("requeued")
            };
            insert_event(&tx, id, *attempt, &event)?;
        }
        tx.execute(
            "UPDATE jobs SET state = 'queued', stage = NULL, done = 0, total = 0 \
             WHERE state = 'running'",
            [],
        )?;
        let queued: Vec<String> = {
            let mut stmt = tx.prepare("SELECT id FROM jobs WHERE state = 'queued' ORDER BY seq")?;
            let rows = stmt.query_map([], |r| r.get(0))?;
            rows.collect::<Result<_>>()?
        };
        tx.commit()?;
        Ok((running.into_iter().map(|r| r.0).collect(), queued))
    }

    /// Every job id, for the startup sweep of folders without a job.
    pub fn ids(&self) -> Result<Vec<String>> {
        let conn = self.conn();
        let mut stmt = conn.prepare("SELECT id FROM jobs")?;
        let rows = stmt.query_map([], |r| r.get(0))?;
        rows.collect()
    }

    /// The events of a job after event `after`, oldest first, at most `limit`.
    pub fn events_after(&self, id: &str, after: i64, limit: usize) -> Result<Vec<Event>> {
        let conn = self.conn();
        let mut stmt = conn.prepare(
            "SELECT id, at, kind, stage, done, total, seconds, message, attempt FROM events \
             WHERE job = ?1 AND id > ?2 ORDER BY id LIMIT ?3",
        )?;
        let rows = stmt.query_map(params![id, after, limit as i64], |r| {
            Ok(Event {
                id: r.get(0)?,
                at: r.get(1)?,
                kind: r.get(2)?,
                stage: r.get(3)?,
                done: r.get::<_, Option<i64>>(4)?.map(|x| x as u64),
                total: r.get::<_, Option<i64>>(5)?.map(|x| x as u64),
                seconds: r.get(6)?,
                message: r.get(7)?,
                attempt: r.get(8)?,
            })
        })?;
        rows.collect()
    }

    /// Jobs per state, every state present.
    pub fn counts(&self) -> Result<Vec<(State, u64)>> {
        let conn = self.conn();
        State::ALL
            .into_iter()
            .map(|s| {
                let n: i64 = conn.query_row(
                    "SELECT COUNT(*) FROM jobs WHERE state = ?1",
                    [s.as_str()],
                    |r| r.get(0),
                )?;
                Ok((s, n as u64))
            })
            .collect()
    }

    pub fn queued(&self) -> Result<u64> {
        let conn = self.conn();
        let n: i64 = conn.query_row(
            "SELECT COUNT(*) FROM jobs WHERE state = 'queued'",
            [],
            |r| r.get(0),
        )?;
        Ok(n as u64)
    }

    /// Per stage: the number of finished runs of it and their total seconds.
    pub fn stage_totals(&self) -> Result<Vec<(String, u64, f64)>> {
        let conn = self.conn();
        let mut stmt = conn.prepare(
            "SELECT stage, COUNT(*), SUM(seconds) FROM events WHERE kind = 'stage_done' \
             GROUP BY stage ORDER BY stage",
        )?;
        let rows = stmt.query_map([], |r| {
            Ok((r.get(0)?, r.get::<_, i64>(1)? as u64, r.get(2)?))
        })?;
        rows.collect()
    }
}

impl NewEvent<'_> {
    pub fn kind(kind: &str) -> NewEvent<'_> {
        NewEvent {
            kind,
            ..Default::default()
        }
    }
}

fn insert_event(conn: &Connection, id: &str, attempt: u32, e: &NewEvent<'_>) -> Result<()> {
    conn.execute(
        "INSERT INTO events (job, at, kind, stage, done, total, seconds, message, attempt) \
         VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)",
        params![
            id,
            now(),
            e.kind,
            e.stage,
            e.done.map(|x| x as i64),
            e.total.map(|x| x as i64),
            e.seconds,
            e.message,
            attempt
        ],
    )?;
    Ok(())
}

/// The finished stages of one attempt, in order.
fn timings(conn: &Connection, id: &str, attempt: u32) -> Result<Vec<Timing>> {
    let mut stmt = conn.prepare(
        "SELECT stage, seconds FROM events WHERE job = ?1 AND attempt = ?2 \
         AND kind = 'stage_done' ORDER BY id",
    )?;
    let rows = stmt.query_map(params![id, attempt], |r| {
        Ok(Timing {
            stage: r.get::<_, Option<String>>(0)?.unwrap_or_default(),
            seconds: r.get::<_, Option<f64>>(1)?.unwrap_or(0.0),
        })
    })?;
    rows.collect()
}

fn job_of_row(r: &Row<'_>) -> Result<Job> {
    let text_err = |k: usize, e: serde_json::Error| {
        rusqlite::Error::FromSqlConversionFailure(k, rusqlite::types::Type::Text, Box::new(e))
    };
    let state: String = r.get(2)?;
    let state = State::parse(&state).ok_or_else(|| {
        rusqlite::Error::FromSqlConversionFailure(
            2,
            rusqlite::types::Type::Text,
            format!("unknown state {state:?}").into(),
        )
    })?;
    let done = r.get::<_, i64>(7)?.max(0) as u64;
    let total = r.get::<_, i64>(8)?.max(0) as u64;
    let options: String = r.get(9)?;
    let report: Option<String> = r.get(10)?;
    let results: String = r.get(13)?;
    let fraction = match state {
        State::Done => 1.0,
        _ if total > 0 => (done as f64 / total as f64).min(1.0),
        _ => 0.0,
    };
    Ok(Job {
        id: r.get(0)?,
        owner: r.get(1)?,
        state,
        progress: StageProgress {
            stage: r.get(6)?,
            done,
            total,
            fraction,
        },
        created: r.get(3)?,
        started: r.get(4)?,
        finished: r.get(5)?,
        timings: Vec::new(),
        options: serde_json::from_str(&options).map_err(|e| text_err(9, e))?,
        attempts: r.get(12)?,
        report: match report {
            Some(t) => Some(serde_json::from_str(&t).map_err(|e| text_err(10, e))?),
            None => None,
        },
        error: r.get(11)?,
        results: serde_json::from_str(&results).map_err(|e| text_err(13, e))?,
    })
}
