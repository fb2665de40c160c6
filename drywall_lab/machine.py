"""The machine a figure was measured on: CPU, cores, GPU, torch, load average and date.

Every timing the project records (``benchmarks/latency.py``, ``benchmarks/placement.py``,
``benchmarks/bert_settings.py``, ``python -m drywall_lab experiment paper``) says where it ran,
because a time means little without the machine and how busy it was. ``describe_machine()``
takes one snapshot; ``Machine.summary()`` is the one line a results file quotes.

>>> cpu_model_from_cpuinfo("processor : 0\\nmodel name : AMD EPYC 7B13\\ncpu MHz : 2450.0\\n")
'AMD EPYC 7B13'
>>> format_load((0.5, 1.25, 2.0))
'0.50, 1.25, 2.00 (1, 5, 15 min)'
"""
from __future__ import annotations

import datetime as dt
import os
import platform
from dataclasses import asdict, dataclass
from pathlib import Path

CPUINFO = Path("/proc/cpuinfo")

#: A load average: the mean number of runnable processes over the last 1, 5 and 15 minutes.
LoadAverage = tuple[float, float, float]


def cpu_model_from_cpuinfo(text: str) -> str | None:
    """The first ``model name`` in the text of ``/proc/cpuinfo`` (x86), else its ``Hardware`` or
    ``Model`` line (ARM boards), else ``None``."""
    fields: dict[str, str] = {}
    for line in text.splitlines():
        key, sep, value = line.partition(":")
        if sep and value.strip():
            fields.setdefault(key.strip().lower(), value.strip())
    for key in ("model name", "hardware", "model"):
        if key in fields:
            return fields[key]
    return None


def cpu_model(cpuinfo: Path = CPUINFO) -> str:
    """The CPU's model name: from ``/proc/cpuinfo`` where there is one, else what ``platform`` says."""
    try:
        found = cpu_model_from_cpuinfo(cpuinfo.read_text(encoding="utf-8", errors="replace"))
    except OSError:
        found = None
    return found or platform.processor() or platform.machine() or "unknown CPU"


def load_average() -> LoadAverage | None:
    """``os.getloadavg()``, or ``None`` where the system does not keep one (Windows)."""
    try:
        one, five, fifteen = os.getloadavg()
    except (AttributeError, OSError):
        return None
    return (one, five, fifteen)


def format_load(load: LoadAverage | None) -> str:
    """``'0.50, 1.25, 2.00 (1, 5, 15 min)'``, or ``'not available'``."""
    if load is None:
        return "not available"
    return ", ".join(f"{x:.2f}" for x in load) + " (1, 5, 15 min)"


def _torch_details() -> tuple[str | None, str | None, int | None]:
    """(torch version, GPU name or None, torch CPU threads); all None where torch is not installed."""
    try:
        import torch
    except ImportError:
        return None, None, None
    gpu = torch.cuda.get_device_name(0) if torch.cuda.is_available() else None
    return torch.__version__, gpu, torch.get_num_threads()


@dataclass(frozen=True)
class Machine:
    """One snapshot of the machine: what it is, and how loaded it was at ``date``."""

    cpu: str
    logical_cores: int
    gpu: str | None  #: the first CUDA device torch sees, None for none
    torch: str | None  #: torch's version, None where torch is not installed
    torch_threads: int | None  #: threads torch uses on the CPU
    python: str
    platform: str
    load_average: LoadAverage | None
    date: str  #: ISO 8601, UTC, to the second

    def summary(self) -> str:
        """One line: ``AMD EPYC, 2 logical cores, no GPU, torch 2.13.0+cpu (2 threads), Python 3.11.7; load ...``."""
        torch = f"torch {self.torch} ({self.torch_threads} threads)" if self.torch else "no torch"
        return (f"{self.cpu}, {self.logical_cores} logical cores, {'GPU ' + self.gpu if self.gpu else 'no GPU'}, "
                f"{torch}, Python {self.python}; load average {format_load(self.load_average)}; {self.date}")

    def markdown_lines(self) -> list[str]:
        """A Markdown bullet list, one field a line, for a results file."""
        shown = asdict(self) | {"gpu": self.gpu or "none", "torch": self.torch or "not installed",
                                "load_average": format_load(self.load_average)}
        return [f"- {name.replace('_', ' ')}: {value}" for name, value in shown.items() if value is not None]


def describe_machine(now: dt.datetime | None = None) -> Machine:
    """A snapshot of this machine now (or at ``now``): CPU, cores, GPU, torch, load average, date."""
    torch_version, gpu, threads = _torch_details()
    when = (now or dt.datetime.now(dt.timezone.utc)).astimezone(dt.timezone.utc)
    return Machine(cpu=cpu_model(), logical_cores=os.cpu_count() or 1, gpu=gpu, torch=torch_version,
                   torch_threads=threads, python=platform.python_version(), platform=platform.platform(),
                   load_average=load_average(), date=when.strftime("%Y-%m-%d %H:%M:%S UTC"))
