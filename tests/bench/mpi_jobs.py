"""Independent benchmark runs across MPI ranks: writes the commands to a jobs file (one shell
line each, stdout and stderr to a log next to its results) and runs it with
`mpirun -np N build/saarcor jobs --mpi FILE` (docs/mpi.md), or without MPI in this process a few at a
time (run_local). Shared by bench_stress.py --mpi N and bench_precision.py [--mpi N]."""
import concurrent.futures as cf
import os
import shlex
import subprocess

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_btl_vader_single_copy_mechanism="none")


def run_jobs(saarcor, jobs, ranks, path):
    """jobs: list of (argv, log path). Raises if any job or the MPI run fails."""
    with open(path, "w") as f:
        for argv, log in jobs:
            f.write(" ".join(shlex.quote(a) for a in argv) + f" >{shlex.quote(log)} 2>&1\n")
    r = subprocess.run(["mpirun", "--oversubscribe", "-np", str(ranks), saarcor, "jobs", "--mpi", path],
                       env=ENV, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"jobs --mpi {path} on {ranks} ranks failed: " + (r.stderr.strip().splitlines() or ["?"])[0])


def run_local(jobs, workers=2):
    """The same jobs without MPI, `workers` at a time, each one's stdout and stderr to its log."""
    def one(job):
        argv, log = job
        with open(log, "w") as f:
            rc = subprocess.run(argv, stdout=f, stderr=subprocess.STDOUT).returncode
        if rc != 0:
            raise RuntimeError(" ".join(argv) + ": " + open(log).read().strip())
    with cf.ThreadPoolExecutor(max_workers=workers) as pool:
        list(pool.map(one, jobs))


def run_all(saarcor, jobs, ranks, path, workers=2):
    """run_jobs on `ranks` MPI ranks if ranks, else run_local."""
    if ranks:
        run_jobs(saarcor, jobs, ranks, path)
    else:
        run_local(jobs, workers)
