#!/usr/bin/env bash
# Installs mdhd as a systemd service: the executable (with its browser UI inside),
# /etc/mdhd/mdhd.json, a generated bearer token in /etc/mdhd/environment, the unit,
# and the mdhd system user. Idempotent: existing config and token are kept.
#
#   sudo deploy/install.sh [--prefix /usr/local] [--binary PATH] [--no-start]
#   deploy/install.sh --destdir DIR ...   # stage into DIR only (no user, no systemctl)
set -euo pipefail
cd "$(dirname "$0")/.."

prefix=/usr/local
destdir=""
binary=""
start=1
while (($#)); do
  case "$1" in
    --prefix) prefix=$2; shift 2 ;;
    --destdir) destdir=$2; shift 2 ;;
    --binary) binary=$2; shift 2 ;;
    --no-start) start=0; shift ;;
    -h|--help) sed -n '2,8p' "$0"; exit 0 ;;
    *) echo "install.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
case "$prefix" in
  /*) ;;
  *) echo "install.sh: --prefix must be an absolute path, not '$prefix'" >&2; exit 2 ;;
esac
if [ -z "$destdir" ] && [ "$(id -u)" -ne 0 ]; then
  echo "install.sh: run as root (or stage with --destdir DIR)" >&2
  exit 2
fi

if [ -z "$binary" ]; then
  binary=build/bin/mdhd
  [ -x "$binary" ] || bash scripts/build.sh release
fi
[ -x "$binary" ] || { echo "install.sh: no executable at $binary" >&2; exit 2; }

root=${destdir%/}
etc=$root/etc/mdhd
install -d -m 0755 "$root$prefix/bin" "$root$prefix/share/doc/mdhd" "$root/etc/systemd/system"
install -d -m 0750 "$etc"
install -m 0755 "$binary" "$root$prefix/bin/mdhd"
install -m 0644 docs/deploy.md "$root$prefix/share/doc/mdhd/deploy.md"
sed "s#/usr/local#$prefix#g" deploy/mdhd.service >"$root/etc/systemd/system/mdhd.service"
chmod 0644 "$root/etc/systemd/system/mdhd.service"

if [ ! -e "$etc/mdhd.json" ]; then
  install -m 0640 deploy/mdhd.json "$etc/mdhd.json"
  echo "install.sh: wrote $etc/mdhd.json" >&2
else
  echo "install.sh: kept $etc/mdhd.json" >&2
fi
if [ ! -e "$etc/environment" ]; then
  # 32 random bytes as hex: the service refuses tokens under 16 characters.
  token=$(od -An -tx1 -N32 /dev/urandom | tr -d ' \n')
  (umask 077 && printf 'MDHD_TOKENS=%s\n' "$token" >"$etc/environment")
  echo "install.sh: wrote a bearer token to $etc/environment (root only)" >&2
else
  echo "install.sh: kept $etc/environment" >&2
fi

# Refuse to install a configuration the service would refuse at start.
(set -a && . "$etc/environment" && set +a &&
  "$root$prefix/bin/mdhd" serve --config "$etc/mdhd.json" --check-config)

[ -z "$destdir" ] || exit 0

if ! getent passwd mdhd >/dev/null; then
  useradd --system --user-group --home-dir /var/lib/mdhd --no-create-home \
    --shell /usr/sbin/nologin mdhd
  echo "install.sh: created the system user mdhd" >&2
fi
chgrp mdhd "$etc" "$etc/mdhd.json"

if [ ! -d /run/systemd/system ]; then
  echo "install.sh: systemd is not running here; start the service by hand:" >&2
  echo "  install -d -o mdhd -g mdhd /var/lib/mdhd && cd /var/lib/mdhd &&" \
    "sudo -u mdhd env \$(cat /etc/mdhd/environment) $prefix/bin/mdhd serve --config /etc/mdhd/mdhd.json" >&2
  exit 0
fi
systemctl daemon-reload
if ((start)); then
  systemctl enable mdhd.service
  systemctl restart mdhd.service
  port=$(sed -n 's/.*"port": *\([0-9]*\).*/\1/p' "$etc/mdhd.json")
  for _ in $(seq 50); do
    if curl -fsS "http://127.0.0.1:${port:-8080}/healthz" >/dev/null 2>&1; then
      echo "install.sh: mdhd is up on port ${port:-8080} (UI: http://<this host>:${port:-8080}/)" >&2
      exit 0
    fi
    sleep 0.2
  done
  echo "install.sh: mdhd did not answer /healthz; see: journalctl -u mdhd" >&2
  exit 1
fi
