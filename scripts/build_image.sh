#!/usr/bin/env bash
# Build the production image with buildah (no Docker engine runs on these machines) and check it:
# the container answers its health check and serves a page a browser test can drive.
#
#   bash scripts/build_image.sh            # build, run, health-check, browser-test, report size
#
# No base image can be pulled here, so a stand-in for python:3.11-slim is made locally with
# debootstrap (Debian bookworm, its python3 3.11 and venv) and passed as BASE_IMAGE. On a machine
# with a registry, `docker build .` uses the real python:3.11-slim.
set -euo pipefail
cd "$(dirname "$0")/.."

IMAGE=${IMAGE:-localhost/dynamics-lab:latest}
BASE=${BASE:-localhost/debian-python:bookworm}
PORT=8501  # the port the image serves and its HEALTHCHECK probes
export STORAGE_DRIVER=${STORAGE_DRIVER:-vfs}

need() { command -v "$1" >/dev/null 2>&1 || { apt-get update -qq; DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$2" >/dev/null; }; }
need buildah buildah
need debootstrap debootstrap

if ! buildah inspect --type image "$BASE" >/dev/null 2>&1; then
  echo "== making the base image $BASE with debootstrap"
  rootfs=$(mktemp -d)
  debootstrap --variant=minbase --include=python3,python3-venv,ca-certificates bookworm "$rootfs" \
    http://deb.debian.org/debian >/dev/null
  rm -rf "$rootfs"/var/cache/apt/archives/*.deb "$rootfs"/var/lib/apt/lists/*
  ln -sf python3 "$rootfs/usr/bin/python"
  ctr=$(buildah from scratch)
  tar -C "$rootfs" -cf "$rootfs.tar" . && buildah add "$ctr" "$rootfs.tar" / >/dev/null && rm -f "$rootfs.tar"
  buildah config --env PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin --cmd python3 "$ctr"
  buildah commit --quiet "$ctr" "$BASE" >/dev/null
  buildah rm "$ctr" >/dev/null
  rm -rf "$rootfs"
fi

if [ -z "${SKIP_BUILD:-}" ]; then
echo "== building $IMAGE"
# The proxy's certificate authority is handed in at build time only (the image does not keep it).
buildah bud --isolation chroot --format docker --layers=false \
  -v /etc/ssl/certs/ca-certificates.crt:/etc/ssl/host-ca.crt:ro \
  --build-arg PIP_CERT=/etc/ssl/host-ca.crt --build-arg BASE_IMAGE="$BASE" \
  -t "$IMAGE" . >/tmp/dynamics-lab-build.log 2>&1 || { tail -30 /tmp/dynamics-lab-build.log; exit 1; }
fi

echo "== image facts"
buildah inspect --type image --format 'user={{.Docker.Config.User}} healthcheck={{.Docker.Config.Healthcheck}}' "$IMAGE"
buildah images --format '{{.Name}}:{{.Tag}} {{.Size}}' "$IMAGE"

echo "== running it (buildah run shares the host's network: it answers on 127.0.0.1:$PORT)"
ctr=$(buildah from "$IMAGE")
cleanup() { kill "$run_pid" 2>/dev/null || true; sleep 1; buildah rm "$ctr" >/dev/null 2>&1 || true; }
trap cleanup EXIT
cmd=$(buildah inspect --type image --format '{{range .Docker.Config.Cmd}}{{.}} {{end}}' "$IMAGE")
buildah run --isolation chroot --user app --workingdir /app "$ctr" -- $cmd &
run_pid=$!
health=$(buildah inspect --type image --format '{{range .Docker.Config.Healthcheck.Test}}{{.}}|{{end}}' "$IMAGE")
for i in $(seq 1 90); do
  if curl -fsS "http://127.0.0.1:$PORT/_stcore/health" 2>/dev/null | grep -q ok; then break; fi
  sleep 1
done
curl -fsS "http://127.0.0.1:$PORT/_stcore/health"; echo " <- /_stcore/health"
echo "healthcheck in the image: $health"
echo "== the image's own HEALTHCHECK command, run inside the container"
buildah run --isolation chroot --user app "$ctr" -- python3 -c "$(echo "$health" | awk -F'|' '{print $4}')" \
  && echo "HEALTHCHECK passes"

echo "== browser test against the container"
APP_URL="http://127.0.0.1:$PORT" .venv/bin/python -m pytest -q tests/test_browser.py -k "each_page and disk_wall or bad_link" -p no:cacheprovider
