"""Independent benchmark runs across MPI ranks: writes the commands to a jobs file (one shell
line each, stdout and stderr to a log next to its results) and runs it with
`mpirun -np N build/saarcor jobs --mpi FILE` (docs/mpi.md). Shared by bench_stress.py --mpi N."""
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
