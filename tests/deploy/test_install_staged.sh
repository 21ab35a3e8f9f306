#!/usr/bin/env bash
# deploy/install.sh staged with --destdir, end to end: the files and their modes, a
# second run keeps the token, systemd accepts the unit, and the staged executable
# serves the UI and guards the API with the generated token.
# Usage: test_install_staged.sh SOURCE_DIR MDHD_BINARY
set -euo pipefail
src=$1
bin=$2
tmp=$(mktemp -d)
server=""
cleanup() {
  [ -z "$server" ] || kill "$server" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

stage=$tmp/root
bash "$src/deploy/install.sh" --destdir "$stage" --binary "$bin" >"$tmp/install1.log" 2>&1 ||
  { cat "$tmp/install1.log"; fail "install.sh --destdir failed"; }
for f in usr/local/bin/mdhd:755 etc/mdhd/mdhd.json:640 etc/mdhd/environment:600 \
  etc/systemd/system/mdhd.service:644 usr/local/share/doc/mdhd/deploy.md:644; do
  path=$stage/${f%%:*}
  [ -f "$path" ] || fail "missing $path"
  mode=$(stat -c %a "$path")
  [ "$mode" = "${f##*:}" ] || fail "$path has mode $mode, wants ${f##*:}"
done
token=$(sed -n 's/^MDHD_TOKENS=//p' "$stage/etc/mdhd/environment")
[[ "$token" =~ ^[0-9a-f]{64}$ ]] || fail "token is not 64 hex digits: '$token'"

bash "$src/deploy/install.sh" --destdir "$stage" --binary "$bin" >"$tmp/install2.log" 2>&1 ||
  { cat "$tmp/install2.log"; fail "second install.sh failed"; }
grep -q "kept .*environment" "$tmp/install2.log" || fail "second run did not keep the token"
[ "$(sed -n 's/^MDHD_TOKENS=//p' "$stage/etc/mdhd/environment")" = "$token" ] ||
  fail "second run changed the token"

# A configuration the service would refuse stops the install.
bad=$tmp/bad
mkdir -p "$bad/etc/mdhd"
echo '{"bind": "0.0.0.0", "colour": "blue"}' >"$bad/etc/mdhd/mdhd.json"
echo 'MDHD_TOKENS=' >"$bad/etc/mdhd/environment"
if bash "$src/deploy/install.sh" --destdir "$bad" --binary "$bin" >"$tmp/bad.log" 2>&1; then
  fail "install.sh accepted a config with an unknown field"
fi
grep -q "colour" "$tmp/bad.log" || { cat "$tmp/bad.log"; fail "the refusal does not name the field"; }

# systemd's own check of the unit (ExecStart pointed at the staged executable).
command -v systemd-analyze >/dev/null || fail "systemd-analyze not found (package systemd)"
unit=$tmp/unit/mdhd.service
mkdir -p "$tmp/unit"
sed "s#/usr/local/bin/mdhd#$stage/usr/local/bin/mdhd#g" "$stage/etc/systemd/system/mdhd.service" >"$unit"
verify=$(systemd-analyze verify "$unit" 2>&1) || { echo "$verify"; fail "systemd-analyze verify failed"; }
if echo "$verify" | grep -q "mdhd.service"; then
  echo "$verify"
  fail "systemd-analyze has remarks on the unit"
fi

# The staged executable on the staged settings, on loopback, a free port and a temp store.
(set -a && . "$stage/etc/mdhd/environment" && set +a &&
  exec "$stage/usr/local/bin/mdhd" serve --config "$stage/etc/mdhd/mdhd.json" \
    --bind 127.0.0.1 --port 0 --data-dir "$tmp/data" --log-file "$tmp/log.jsonl") \
  >"$tmp/serve.out" 2>&1 &
server=$!
port=""
for _ in $(seq 100); do
  port=$(sed -n 's/.*listening on 127.0.0.1:\([0-9]*\).*/\1/p' "$tmp/serve.out")
  [ -n "$port" ] && break
  sleep 0.1
done
[ -n "$port" ] || { cat "$tmp/serve.out"; fail "the staged service did not start"; }
status() { curl -s -o /dev/null -w '%{http_code}' "$@"; }
base=http://127.0.0.1:$port
[ "$(status "$base/healthz")" = 200 ] || fail "/healthz"
[ "$(status "$base/")" = 200 ] || fail "the UI page"
curl -s "$base/" | grep -qi "<!doctype html>" || fail "the UI page is not HTML"
[ "$(status "$base/api/v1/jobs")" = 401 ] || fail "the API answered without a token"
[ "$(status -H "Authorization: Bearer $token" "$base/api/v1/jobs")" = 200 ] ||
  fail "the API refused the generated token"
echo "deploy_install_staged: ok (port $port)"
