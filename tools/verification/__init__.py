"""The verification harness: case registry, runner and report."""
