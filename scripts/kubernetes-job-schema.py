#!/usr/bin/env python3
"""Writes the standalone JSON Schema of a Kubernetes batch/v1 Job that
crates/dtg-vib/tests/fleet_plan.rs validates `fleet plan --engine kubernetes`
against: the Job schema of one Kubernetes version from the PyPI package
kubernetes-validate (Apache-2.0), with only the definitions the Job reaches
and without descriptions (which do not validate anything).

    pip download --no-deps kubernetes-validate==1.37.0 -d /tmp/kv
    python3 scripts/kubernetes-job-schema.py /tmp/kv/kubernetes_validate-1.37.0-py3-none-any.whl v1.33.0 \
        > crates/dtg-vib/tests/fixtures/kubernetes/job-batch-v1.33.json
"""
import json
import sys
import zipfile


def main(wheel, version):
    base = f"kubernetes_validate/kubernetes-json-schema/{version}-local-strict/"
    with zipfile.ZipFile(wheel) as z:
        job = json.loads(z.read(base + "job-batch-v1.json"))
        defs = json.loads(z.read(base + "_definitions.json"))["$defs"]
    need = set()

    def walk(x):
        if isinstance(x, dict):
            for k, v in x.items():
                if k == "$ref":
                    name = v.split("#/$defs/")[1]
                    if name not in need:
                        need.add(name)
                        walk(defs[name])
                else:
                    walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)

    def clean(x):
        if isinstance(x, dict):
            return {
                k: ("#/$defs/" + v.split("#/$defs/")[1]) if k == "$ref" else clean(v)
                for k, v in x.items()
                if k != "description"
            }
        if isinstance(x, list):
            return [clean(v) for v in x]
        return x

    walk(job)
    out = clean(job)
    out["$schema"] = "https://json-schema.org/draft/2020-12/schema"
    out["$defs"] = {n: clean(defs[n]) for n in sorted(need)}
    print(json.dumps(out, separators=(",", ":"), sort_keys=True))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
