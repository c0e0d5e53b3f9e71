# Sourced by the setup scripts: apt-get calls that tell a failing package
# source apart from everything else. jd_apt_update leaves its output in
# $jd_apt_log; jd_apt_index_failure ARCH prints why ARCH's index failed
# (empty when it did not).
jd_apt_log=${TMPDIR:-/tmp}/jade-apt.$$.log
trap 'rm -f "$jd_apt_log" "$jd_apt_log.install"' EXIT

jd_apt_update()
{
    opts=""
    for a in $1; do opts="$opts -o APT::Architectures::=$a"; done
    # shellcheck disable=SC2086
    apt-get update -q ${JADE_APT_OPTS:-} $opts > "$jd_apt_log" 2>&1 || true
}

# "E: Failed to fetch URL/dists/SUITE/main/binary-armhf/Packages.xz  File has
# unexpected size ..." names the architecture in the index's path; a
# Release file that fails fails every architecture of that suite.
jd_apt_index_failure()
{
    grep -E '^(E|W): (Failed to fetch|Some index files)' "$jd_apt_log" 2>/dev/null |
        grep -E "binary-$1/|/(In)?Release" | head -1 |
        sed -E 's/^(E|W): Failed to fetch [^ ]+ +//; s/ +\[IP: [^]]*\]//' || true
}

# jd_apt_install "OPTIONS" PACKAGE...: installs, retrying from the release
# suite (when the architectures' security indexes disagree, the release
# suite has versions that exist for all of them). Dry runs only say it.
jd_apt_install()
{
    opts=$1
    shift
    [ $# -eq 0 ] && return 0
    if [ -n "${JADE_CROSS_DRY:-}" ]; then echo "would install: $*"; return 0; fi
    echo "installing: $*"
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends ${JADE_APT_OPTS:-} $opts "$@" > "$jd_apt_log.install" 2>&1 ||
        apt-get install -y -q --no-install-recommends ${JADE_APT_OPTS:-} $opts -t bookworm "$@" \
            > "$jd_apt_log.install" 2>&1
}

jd_apt_last_error()
{
    grep -E '^E: ' "$jd_apt_log.install" 2>/dev/null | tail -1 | sed 's/^E: //'
}
