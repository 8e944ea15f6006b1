# SPDX-License-Identifier: GPL-3.0-or-later
"""The process tree as /proc shows it (Linux): what the fault campaign and the fault test kill.

Plain functions, no state; a process that ends while it is read is skipped.
"""
import os


def _stat_fields(pid):
    """The fields after the command name of /proc/PID/stat (state, ppid, pgrp, session, ...)."""
    with open("/proc/%s/stat" % pid) as f:
        return f.read().rsplit(")", 1)[1].split()


def descendants(pid):
    """Every descendant of pid (children, grandchildren, ...), parents before their children."""
    children = {}
    for p in os.listdir("/proc"):
        if not p.isdigit():
            continue
        try:
            children.setdefault(int(_stat_fields(p)[1]), []).append(int(p))
        except OSError:
            pass
    out, todo = [], [pid]
    while todo:
        for c in children.get(todo.pop(), []):
            out.append(c)
            todo.append(c)
    return out


def comm_name(pid):
    """The process's command name (/proc/PID/comm), "" once it has ended."""
    try:
        with open("/proc/%d/comm" % pid) as f:
            return f.read().strip()
    except OSError:
        return ""


def session_pids(sid):
    """Every process of session sid but its leader."""
    out = []
    for p in os.listdir("/proc"):
        if not p.isdigit():
            continue
        try:
            if int(_stat_fields(p)[3]) == sid and int(p) != sid:
                out.append(int(p))
        except OSError:
            pass
    return out
