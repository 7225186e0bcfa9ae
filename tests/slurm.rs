//! A study on a real Slurm cluster, through the batch script `slipfront study --slurm-array`
//! writes, gives the files the same study gives run on one machine, byte for byte: every
//! member's catalogs and record, `events.csv`, `summary.md` and `summary.png`, and recordings
//! whose series export to the same table. So does a submission disturbed as a cluster disturbs
//! one: a task cancelled midway (the job that writes the tables then names the members it left
//! missing and fails), a task requeued midway by `scontrol requeue` (run again, it keeps the
//! members it had finished and counts none twice), and the cancelled task resubmitted alone.
//! The folder Slurm filled, with its logs, is then served by `rerun server` and queried as a
//! colleague would, to the same answers as the local folder.
//!
//! The cluster is Debian's `slurm-wlm` with `munge`, installed with `apt-get` if missing, run as
//! root without systemd: `munged`, `slurmctld` and `slurmd` on this machine, configured under a
//! temporary folder (their own key, socket, ports, state and logs), started as children of the
//! test and stopped by their process ids, after every job left is cancelled. Where Slurm cannot
//! be installed or started (not root, no network), the test says SKIPPED, unless
//! `SLIPFRONT_REQUIRE_SLURM` is set (as in CI), which makes that a failure.

mod common;

use std::collections::BTreeMap;
use std::io::Read;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{binary, paper_study, read_study, serve_study, study_files};

/// How long any one wait on the cluster may take before the test fails.
const PATIENCE: Duration = Duration::from_secs(240);

/// The programs the test needs, and the Debian packages that hold them.
const PROGRAMS: [&str; 7] = ["munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol", "scancel"];

fn skip(why: &str) {
    assert!(
        std::env::var_os("SLIPFRONT_REQUIRE_SLURM").is_none(),
        "Slurm is required (SLIPFRONT_REQUIRE_SLURM is set): {why}"
    );
    eprintln!("SKIPPED: the study on Slurm did not run: {why}");
}

fn installed(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Installs `slurm-wlm` and `munge` from Debian if a program is missing (`apt-get update` first
/// if the package lists do not have them). Debian's scripts start no daemon where there is no
/// init system, so the only daemons are those the test starts.
fn install() -> Result<(), String> {
    if PROGRAMS.iter().all(|p| installed(p)) {
        return Ok(());
    }
    let started = Instant::now();
    eprintln!("slurm: installing slurm-wlm and munge with apt-get");
    let apt = |args: &[&str]| {
        Command::new("apt-get")
            .args(["-o", "DPkg::Lock::Timeout=300", "-q", "-y"])
            .args(args)
            .env("DEBIAN_FRONTEND", "noninteractive")
            .output()
            .map_err(|e| format!("apt-get: {e}"))
    };
    let packages = ["install", "--no-install-recommends", "slurm-wlm", "munge"];
    let mut out = apt(&packages)?;
    if !out.status.success() {
        apt(&["update"])?;
        out = apt(&packages)?;
    }
    if !out.status.success() {
        return Err(format!("apt-get install slurm-wlm munge failed: {}", String::from_utf8_lossy(&out.stderr)));
    }
    eprintln!("slurm: installed in {:.1} s", started.elapsed().as_secs_f64());
    match PROGRAMS.iter().find(|p| !installed(p)) {
        Some(missing) => Err(format!("{missing} is still missing after apt-get install slurm-wlm munge")),
        None => Ok(()),
    }
}

/// A free TCP port on this machine.
fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port()
}

/// A single-node Slurm cluster under `dir`, its daemons children of the test.
struct Cluster {
    dir: PathBuf,
    conf: PathBuf,
    /// The daemons by name, in the order started.
    daemons: Vec<(&'static str, Child)>,
}

impl Cluster {
    fn start(dir: &Path) -> Result<Self, String> {
        let name = std::fs::read_to_string("/proc/sys/kernel/hostname").map_err(|e| e.to_string())?;
        let host = name.trim().split('.').next().unwrap_or_default().to_string();
        let path = |name: &str| dir.join(name).display().to_string();
        for sub in ["munge", "state", "spool"] {
            std::fs::create_dir_all(dir.join(sub)).map_err(|e| e.to_string())?;
        }
        // munge's own key, readable by root alone, and its socket in a folder all may enter.
        let mut key = [0u8; 128];
        std::fs::File::open("/dev/urandom").and_then(|mut f| f.read_exact(&mut key)).map_err(|e| e.to_string())?;
        std::fs::write(dir.join("munge/munge.key"), key).map_err(|e| e.to_string())?;
        std::fs::set_permissions(dir.join("munge/munge.key"), std::fs::Permissions::from_mode(0o600))
            .map_err(|e| e.to_string())?;
        std::fs::set_permissions(dir.join("munge"), std::fs::Permissions::from_mode(0o755))
            .map_err(|e| e.to_string())?;
        let socket = path("munge/munge.socket");
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        // As a site's, but for a scheduler that looks at the queue every second, and a requeued
        // job that may start again 10 s after its end rather than 2 min (the lifetime of the
        // credential Slurm revokes when it kills a job, `cred_expire`).
        let conf = format!(
            "ClusterName=slipfront\n\
             SlurmctldHost={host}(127.0.0.1)\n\
             SlurmctldPort={ctld}\n\
             SlurmdPort={slurmd}\n\
             SlurmUser=root\n\
             SlurmdUser=root\n\
             AuthType=auth/munge\n\
             AuthInfo=socket={socket},cred_expire=10\n\
             CredType=cred/munge\n\
             StateSaveLocation={state}\n\
             SlurmdSpoolDir={spool}\n\
             SlurmctldPidFile={dir}/slurmctld.pid\n\
             SlurmdPidFile={dir}/slurmd.pid\n\
             SlurmctldLogFile={dir}/slurmctld.log\n\
             SlurmdLogFile={dir}/slurmd.log\n\
             ProctrackType=proctrack/linuxproc\n\
             TaskPlugin=task/none\n\
             JobAcctGatherType=jobacct_gather/none\n\
             AccountingStorageType=accounting_storage/none\n\
             JobCompType=jobcomp/filetxt\n\
             JobCompLoc={dir}/jobs.txt\n\
             SelectType=select/cons_tres\n\
             SelectTypeParameters=CR_CPU\n\
             SchedulerType=sched/builtin\n\
             SchedulerParameters=sched_interval=1\n\
             MpiDefault=none\n\
             ReturnToService=2\n\
             KillWait=5\n\
             SlurmdParameters=config_overrides\n\
             NodeName={host} NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN\n\
             PartitionName=batch Nodes=ALL Default=YES MaxTime=INFINITE State=UP\n",
            ctld = free_port(),
            slurmd = free_port(),
            state = path("state"),
            spool = path("spool"),
            dir = dir.display(),
        );
        let conf_path = dir.join("slurm.conf");
        std::fs::write(&conf_path, conf).map_err(|e| e.to_string())?;
        let mut cluster = Self { dir: dir.to_path_buf(), conf: conf_path.clone(), daemons: Vec::new() };
        let conf = conf_path.display().to_string();
        cluster.spawn(
            "munged",
            &[
                "--foreground",
                "--force",
                &format!("--socket={socket}"),
                &format!("--key-file={}", path("munge/munge.key")),
                &format!("--pid-file={}", path("munge/munged.pid")),
                &format!("--log-file={}", path("munge/munged.log")),
                &format!("--seed-file={}", path("munge/munged.seed")),
            ],
        )?;
        cluster.wait_for("munged's socket", |_| dir.join("munge/munge.socket").exists())?;
        cluster.spawn("slurmctld", &["-D", "-f", &conf])?;
        cluster.spawn("slurmd", &["-D", "-f", &conf, "-N", &host])?;
        cluster.wait_for("the node to be idle", |cluster| {
            cluster
                .output("sinfo", &["-h", "-o", "%T"])
                .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "idle")
        })?;
        Ok(cluster)
    }

    /// Starts a daemon in the foreground, its output in `<name>.out`.
    fn spawn(&mut self, name: &'static str, args: &[&str]) -> Result<(), String> {
        let log = std::fs::File::create(self.dir.join(format!("{name}.out"))).map_err(|e| e.to_string())?;
        let child = Command::new(name)
            .args(args)
            .env("SLURM_CONF", &self.conf)
            .stdin(Stdio::null())
            .stdout(log.try_clone().map_err(|e| e.to_string())?)
            .stderr(log)
            .spawn()
            .map_err(|e| format!("{name}: {e}"))?;
        self.daemons.push((name, child));
        Ok(())
    }

    /// Waits until `ready` holds, or fails naming a daemon that has ended, or at [`PATIENCE`].
    fn wait_for(&mut self, what: &str, mut ready: impl FnMut(&Self) -> bool) -> Result<(), String> {
        let started = Instant::now();
        loop {
            if ready(self) {
                return Ok(());
            }
            for (name, child) in &mut self.daemons {
                if let Ok(Some(status)) = child.try_wait() {
                    let log = std::fs::read_to_string(self.dir.join(format!("{name}.out"))).unwrap_or_default();
                    return Err(format!("{name} ended ({status}) while waiting for {what}:\n{log}"));
                }
            }
            if started.elapsed() > PATIENCE {
                return Err(format!("{what}: not after {PATIENCE:?}"));
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// A Slurm client command against this cluster.
    fn output(&self, program: &str, args: &[&str]) -> std::io::Result<Output> {
        Command::new(program).args(args).env("SLURM_CONF", &self.conf).output()
    }

    /// Runs a client command that must succeed; its standard output.
    fn run(&self, program: &str, args: &[&str]) -> String {
        let out = self.output(program, args).unwrap_or_else(|e| panic!("{program}: {e}"));
        assert!(out.status.success(), "{program} {args:?}: {}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8(out.stdout).unwrap()
    }

    /// The jobs in the queue, one line each: `ID STATE`.
    fn queue(&self) -> String {
        match self.output("squeue", &["-h", "-o", "%i %T"]) {
            Ok(out) if out.status.success() => String::from_utf8_lossy(&out.stdout).into_owned(),
            Ok(out) => format!("squeue failed: {}", String::from_utf8_lossy(&out.stderr)),
            Err(e) => format!("squeue: {e}"),
        }
    }

    /// Waits until no job is left in the queue.
    fn wait_empty(&mut self, what: &str) {
        let started = Instant::now();
        let mut last = String::new();
        let ok = self.wait_for(what, |cluster| {
            last = cluster.queue();
            last.trim().is_empty()
        });
        assert!(ok.is_ok(), "{what}: {ok:?}; the queue: {last}");
        eprintln!("slurm: {what} in {:.1} s", started.elapsed().as_secs_f64());
    }

    /// Every job end the cluster logged (`jobcomp/filetxt`), in order, as `Key=Value` fields.
    fn ended(&self) -> Vec<BTreeMap<String, String>> {
        let text = std::fs::read_to_string(self.dir.join("jobs.txt")).unwrap_or_default();
        text.lines()
            .map(|line| {
                line.split(' ')
                    .filter_map(|field| field.split_once('='))
                    .map(|(k, v)| (k.to_string(), v.to_string()))
                    .collect()
            })
            .collect()
    }
}

impl Drop for Cluster {
    /// Cancels the jobs left, then stops the daemons the test started, by their process ids:
    /// SIGTERM, then SIGKILL for any still running 20 s later.
    fn drop(&mut self) {
        let _ = self.output("scancel", &["--user=root"]);
        let started = Instant::now();
        while started.elapsed() < Duration::from_secs(30)
            && self.output("squeue", &["-h"]).is_ok_and(|o| o.status.success() && !o.stdout.is_empty())
        {
            std::thread::sleep(Duration::from_millis(200));
        }
        for (_, child) in self.daemons.iter_mut().rev() {
            let _ = Command::new("kill").args(["-TERM", &child.id().to_string()]).status();
            let deadline = Instant::now() + Duration::from_secs(20);
            while child.try_wait().is_ok_and(|s| s.is_none()) && Instant::now() < deadline {
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
    }
}

/// Runs `slipfront ARGS`, which must succeed; its standard output.
fn slipfront(args: &[&str]) -> String {
    let out = binary().args(args).output().unwrap();
    assert!(out.status.success(), "slipfront {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// Writes the study's batch script into `out` (2 tasks of 1 core) and returns its path.
fn array_script(study: &Path, out: &Path) -> PathBuf {
    let text = slipfront(&[
        "study",
        study.to_str().unwrap(),
        "--slurm-array",
        "2",
        "--jobs",
        "1",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    let script = out.join("small/slurm/small.sbatch");
    assert!(text.contains(&script.display().to_string()) && script.is_file(), "{text}");
    script
}

/// Submits `script` as docs/studies.md does (a partition and a time limit on the command line),
/// with `extra` options; the array's job id.
fn submit(cluster: &Cluster, script: &Path, extra: &[&str]) -> String {
    let mut args = vec!["--parsable", "--partition=batch", "--time=00:20:00"];
    args.extend_from_slice(extra);
    args.push(script.to_str().unwrap());
    cluster.run("sbatch", &args).trim().to_string()
}

/// The jobs of the summary that ended, with their states.
fn summary_jobs(cluster: &Cluster) -> Vec<String> {
    cluster
        .ended()
        .into_iter()
        .filter(|job| job.get("Name").is_some_and(|n| n == "small-summary"))
        .map(|job| job["JobState"].clone())
        .collect()
}

/// The ends logged of array `job`'s task `task`, in order.
fn task_ends(cluster: &Cluster, job: &str, task: usize) -> Vec<String> {
    cluster
        .ended()
        .into_iter()
        .filter(|j| j.get("ArrayJobId").is_some_and(|a| a == job) && j.get("ArrayTaskId") == Some(&task.to_string()))
        .map(|j| j["JobState"].clone())
        .collect()
}

fn done(folder: &Path, member: usize) -> bool {
    folder.join(format!("member-{member:04}.done.toml")).exists()
}

/// Each member's recording exported to CSV (`slipfront export`), by member.
fn exported(folder: &Path, into: &Path) -> Vec<Vec<u8>> {
    std::fs::create_dir_all(into).unwrap();
    (0..6)
        .map(|m| {
            let table = into.join(format!("member-{m}.csv"));
            let rrd = folder.join(format!("member-{m:04}.rrd"));
            slipfront(&["export", rrd.to_str().unwrap(), "--out", table.to_str().unwrap()]);
            std::fs::read(table).unwrap()
        })
        .collect()
}

#[test]
fn a_study_on_slurm_gives_the_local_files_through_a_cancelled_and_a_requeued_task() {
    if let Err(why) = install() {
        return skip(&why);
    }
    let dir = std::env::temp_dir().join(format!("slipfront-slurm-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // The paper case for its 1000 s, 2 sweep rows of 3 members: about 1.7 s a member.
    let study = paper_study(&dir, 3, "");
    let local = dir.join("local");
    slipfront(&["study", study.to_str().unwrap(), "--out-dir", local.to_str().unwrap(), "--jobs", "2", "--quiet"]);
    let expected = study_files(&local.join("small"));
    assert_eq!(
        expected.len(),
        6 * 3 + 3,
        "6 members × (events, ruptures, record) + events.csv, summary.md, summary.png"
    );

    let started = Instant::now();
    let mut cluster = match Cluster::start(&dir.join("cluster")) {
        Ok(cluster) => cluster,
        Err(why) => return skip(&format!("the cluster did not start: {why}")),
    };
    eprintln!("slurm: munged, slurmctld and slurmd up, the node idle, in {:.1} s", started.elapsed().as_secs_f64());

    // The script submitted as written: the same files as the local study.
    let clean = dir.join("clean");
    let script = array_script(&study, &clean);
    let job = submit(&cluster, &script, &[]);
    cluster.wait_empty("the array of 2 tasks and the job writing the tables");
    assert_eq!(task_ends(&cluster, &job, 1), ["COMPLETED"]);
    assert_eq!(task_ends(&cluster, &job, 2), ["COMPLETED"]);
    assert_eq!(summary_jobs(&cluster), ["COMPLETED"], "one job wrote the tables, after both tasks");
    let log = std::fs::read_to_string(clean.join(format!("small/slurm/small-{job}_1.out"))).unwrap();
    assert!(log.contains("task 1 of 2") && log.contains("3 members run (0 failed)"), "{log}");
    assert!(study_files(&clean.join("small")) == expected, "the study run by Slurm differs from the local one");
    assert_eq!(
        exported(&clean.join("small"), &dir.join("tables/clean")),
        exported(&local.join("small"), &dir.join("tables/local"))
    );

    // Disturbed: task 2 cancelled after its first member, task 1 requeued after its first.
    let disturbed = dir.join("disturbed");
    let folder = disturbed.join("small");
    let script = array_script(&study, &disturbed);
    let job = submit(&cluster, &script, &[]);
    let (mut cancelled, mut requeued) = (false, false);
    let poll = Instant::now();
    while !(cancelled && requeued) {
        assert!(poll.elapsed() < PATIENCE, "the tasks did not finish their first members: {}", cluster.queue());
        if !cancelled && done(&folder, 1) {
            cluster.run("scancel", &[&format!("{job}_2")]);
            cancelled = true;
        }
        if !requeued && done(&folder, 0) {
            cluster.run("scontrol", &["requeue", &format!("{job}_1")]);
            requeued = true;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    cluster.wait_empty("the disturbed array and the job writing the tables");
    assert_eq!(task_ends(&cluster, &job, 2), ["CANCELLED"]);
    let ends = task_ends(&cluster, &job, 1);
    assert!(ends.len() == 2 && ends[1] == "COMPLETED", "task 1 requeued once, then completed: {ends:?}");
    let log = std::fs::read_to_string(folder.join(format!("slurm/small-{job}_1.out"))).unwrap();
    assert!(log.contains("DUE TO JOB REQUEUE") && log.contains("attempt 2,"), "{log}");
    let again = &log[log.find("attempt 2,").unwrap()..];
    assert!(
        again.contains("--resume: 1 member verified and kept")
            || again.contains("--resume: 2 members verified and kept"),
        "the requeued task kept the members it had finished: {log}"
    );
    // The job that writes the tables ran once for the array, requeue and all, and failed,
    // naming what the cancelled task left missing: members of shard 2 only.
    assert_eq!(summary_jobs(&cluster), ["COMPLETED", "FAILED"]);
    let summary = std::fs::read_to_string(folder.join("summary.md")).unwrap();
    let missing: Vec<usize> = (0..6).filter(|&m| !done(&folder, m)).collect();
    assert!(!missing.is_empty() && missing.iter().all(|m| m % 2 == 1), "the cancel came too late: {missing:?}");
    assert!(
        summary.contains(&format!("{} of 6 members finished, 0 failed, {} not run", 6 - missing.len(), missing.len())),
        "{summary}"
    );
    for m in &missing {
        assert!(
            summary.contains(&format!("- member-{m:04} (")) && summary.contains("no record: not run, or interrupted"),
            "{summary}"
        );
    }

    // The cancelled task resubmitted alone completes the study: the local files again.
    let job = submit(&cluster, &script, &["--array=2"]);
    cluster.wait_empty("the resubmitted task and the job writing the tables");
    assert_eq!(task_ends(&cluster, &job, 2), ["COMPLETED"]);
    let log = std::fs::read_to_string(folder.join(format!("slurm/small-{job}_2.out"))).unwrap();
    assert!(log.contains(&format!("--resume: {} verified and kept", members(3 - missing.len()))), "{log}");
    assert_eq!(summary_jobs(&cluster), ["COMPLETED", "FAILED", "COMPLETED"]);
    assert!(study_files(&folder) == expected, "the disturbed and resubmitted study differs from the local one");
    drop(cluster);

    // The folder Slurm filled, logs and all, served by `rerun server` and queried from another
    // process: the members' parameters and series as the local folder gives them.
    let Some(served) = serve_study(&folder) else { return };
    let Some(read) = read_study(local.join("small").to_str().unwrap()) else { return };
    assert_eq!(served.lines().filter(|l| l.starts_with("segment,")).count(), 6, "{served}");
    assert_eq!(served, read);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `1 member`, `2 members`.
fn members(n: usize) -> String {
    if n == 1 { "1 member".into() } else { format!("{n} members") }
}
