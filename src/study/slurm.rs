//! A study as a Slurm job array: the batch script `slipfront study STUDY.toml --slurm-array N`
//! writes, for the user to submit with `sbatch`.
//!
//! Task `I` of the array runs `--shard I/N --resume` with `--jobs` members at a time on as many
//! cores (`--cpus-per-task`), so a task run again (resubmitted alone or with the whole array, or
//! requeued by Slurm) keeps the members that verify and runs only the others; a member is never
//! counted twice, since the tables count each member of the study once, by its own record
//! ([`crate::study::record`]). The first task to start submits one more job, which waits for
//! every task of its array (`--dependency=afterany`) and writes the tables with `--summarize`:
//! it names the members still missing and fails if any member is missing or failed. It waits
//! for every task to end rather than to succeed (`afterok`), because a member that fails fails
//! again when run again: with `afterok` such a study would never get its tables, and a
//! cancelled task would leave no word of which members it took with it.
//!
//! Every path in the script is absolute, so it runs from any folder on a file system the nodes
//! share; the logs go to `<out-dir>/<study>/slurm/`.

use std::path::{Path, PathBuf};

use crate::study::summary::plural;

/// What the script runs.
pub struct ArrayJob<'a> {
    /// The `slipfront` binary the tasks run.
    pub slipfront: &'a Path,
    /// The study file and the `--out-dir`, absolute.
    pub study_file: &'a Path,
    pub out_dir: &'a Path,
    /// The study's name (its file's stem), which names its folder, jobs and logs.
    pub name: &'a str,
    /// The tasks of the array (shards) and the members each runs at once (its cores).
    pub tasks: usize,
    pub jobs: usize,
    /// The study's members.
    pub members: usize,
}

/// Where the script and the jobs' logs go: `<out-dir>/<study>/slurm/`.
pub fn folder(out_dir: &Path, name: &str) -> PathBuf {
    out_dir.join(name).join("slurm")
}

/// The path of the script: `<out-dir>/<study>/slurm/<study>.sbatch`.
pub fn script_path(out_dir: &Path, name: &str) -> PathBuf {
    folder(out_dir, name).join(format!("{name}.sbatch"))
}

/// Refuses a task count the study cannot use: at least 1, at most one task per member.
pub fn check_tasks(tasks: usize, members: usize) -> Result<(), String> {
    if tasks == 0 {
        return Err("--slurm-array 0: an array has at least 1 task".into());
    }
    if tasks > members {
        return Err(format!(
            "--slurm-array {tasks}: the study has {members} members, so at most {members} tasks have a member to run"
        ));
    }
    Ok(())
}

/// Refuses a path that a `#SBATCH` line cannot hold as written: Slurm reads `%` in a log's name
/// as a pattern, and splits the line at blanks.
pub fn check_path(path: &Path, what: &str) -> Result<(), String> {
    let text = path.to_str().ok_or_else(|| format!("{what} {} is not valid UTF-8", path.display()))?;
    match text.chars().find(|c| c.is_whitespace() || c.is_control() || "%'\"\\".contains(*c)) {
        Some(c) => Err(format!(
            "{what} {text} holds {c:?}, which a #SBATCH line cannot hold as written: give a path without \
             blanks, quotes, backslashes or %"
        )),
        None => Ok(()),
    }
}

/// `text` quoted for a POSIX shell: in single quotes, each `'` written as `'\''`.
fn quoted(text: &Path) -> String {
    format!("'{}'", text.to_string_lossy().replace('\'', r"'\''"))
}

/// The batch script.
pub fn script(job: &ArrayJob<'_>) -> String {
    let name = job.name;
    let logs = folder(job.out_dir, name);
    let (slipfront, study, out_dir) = (quoted(job.slipfront), quoted(job.study_file), quoted(job.out_dir));
    let (tasks, jobs) = (job.tasks, job.jobs);
    let script = script_path(job.out_dir, name);
    format!(
        r#"#!/bin/bash
# The study {study_file} as a Slurm job array of {tasks_text} of {cores}: {members},
# at most {per_task} per task, into {out_dir_text}/{name}/. Written by slipfront study --slurm-array.
# Submit it with sbatch; options on its command line (a partition, a time limit, an account)
# take precedence over the lines below:
#
#   sbatch --partition=NAME --time=HH:MM:SS {script}
#
# Task I runs shard I/{tasks} of the study (its members whose index is I-1 modulo {tasks}) with
# --resume. The first task to start submits a job that waits for every task to end (afterany)
# and writes the study's tables (summary.md, events.csv, summary.png), naming the members
# missing; that job fails if any member is missing or failed. Run a task that failed or was
# cancelled again by resubmitting it alone (sbatch --array=I ...) or the whole array: the
# members that are done are kept, neither run nor counted twice.
#
#SBATCH --job-name={name}
#SBATCH --array=1-{tasks}
#SBATCH --ntasks=1
#SBATCH --cpus-per-task={jobs}
#SBATCH --output={logs_text}/{name}-%A_%a.out
#SBATCH --open-mode=append

: "${{SLURM_ARRAY_TASK_ID:?this script is a Slurm job array: submit it with sbatch}}"
slipfront={slipfront}
study={study}
out_dir={out_dir}
logs={logs}
name={name_quoted}
# The job that writes the tables reads every member's files on one core; add a time limit here
# (--time=00:30:00) if your site asks for one.
summary_options=(--ntasks=1 --cpus-per-task=1)

echo "slipfront study $name: task $SLURM_ARRAY_TASK_ID of {tasks} (job ${{SLURM_ARRAY_JOB_ID}}_$SLURM_ARRAY_TASK_ID)," \
    "attempt $((${{SLURM_RESTART_COUNT:-0}} + 1)), on $(hostname) at $(date '+%Y-%m-%d %H:%M:%S')"
# One summary job per array: the first task to start makes this folder, which no other task
# (nor this one, requeued) can make again.
marker="$logs/summary-after-$SLURM_ARRAY_JOB_ID"
if mkdir "$marker" 2>/dev/null; then
    options=("${{summary_options[@]}}")
    [ -n "${{SLURM_JOB_PARTITION:-}}" ] && options+=(--partition="$SLURM_JOB_PARTITION")
    [ -n "${{SLURM_JOB_ACCOUNT:-}}" ] && options+=(--account="$SLURM_JOB_ACCOUNT")
    if summary=$(sbatch --parsable --job-name="$name-summary" --dependency="afterany:$SLURM_ARRAY_JOB_ID" \
        --output="$logs/$name-summary-%j.out" "${{options[@]}}" <<'SUMMARY'
#!/bin/bash
exec {slipfront} study {study} --out-dir {out_dir} --summarize
SUMMARY
    ); then
        echo "slipfront study $name: job $summary writes the tables once every task of $SLURM_ARRAY_JOB_ID has ended"
    else
        rmdir "$marker"
        echo "slipfront study $name: could not submit the job that writes the tables; once every task has ended, run" >&2
        echo "  $slipfront study $study --out-dir $out_dir --summarize" >&2
    fi
fi
exec "$slipfront" study "$study" --out-dir "$out_dir" --resume --shard "$SLURM_ARRAY_TASK_ID/{tasks}" \
    --jobs "${{SLURM_CPUS_PER_TASK:-{jobs}}}"
"#,
        study_file = job.study_file.display(),
        out_dir_text = job.out_dir.display(),
        members = plural(job.members, "member"),
        tasks_text = plural(tasks, "task"),
        cores = plural(jobs, "core"),
        per_task = job.members.div_ceil(tasks),
        script = script.display(),
        logs_text = logs.display(),
        logs = quoted(&logs),
        name_quoted = quoted(Path::new(name)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_quoted_reaches_a_program_through_the_shell_as_it_was() {
        for path in ["/a/it's", "/a b/$HOME/`x`/\"q\"/*", "/plain"] {
            let printed = std::process::Command::new("sh")
                .arg("-c")
                .arg(format!("printf %s {}", quoted(Path::new(path))))
                .output();
            assert_eq!(String::from_utf8_lossy(&printed.unwrap().stdout), path);
        }
    }

    #[test]
    fn paths_a_sbatch_line_cannot_hold_are_refused() {
        assert!(check_path(Path::new("/scratch/me/runs"), "--out-dir").is_ok());
        for bad in ["/scratch/my runs", "/scratch/100%", "/scratch/it's"] {
            let error = check_path(Path::new(bad), "--out-dir").unwrap_err();
            assert!(error.contains(bad) && error.contains("#SBATCH"), "{error}");
        }
    }

    #[test]
    fn an_array_has_a_member_for_every_task() {
        assert!(check_tasks(4, 4).is_ok());
        assert_eq!(
            check_tasks(5, 4).unwrap_err(),
            "--slurm-array 5: the study has 4 members, so at most 4 tasks have a member to run"
        );
        assert!(check_tasks(0, 4).is_err());
    }
}
