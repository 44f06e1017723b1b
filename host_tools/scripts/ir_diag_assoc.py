"""Tracks against truth for the IR diagnosis scripts (ir_cloud_diag.py, ir_real_diag.py).

A track is associated with a truth object when, at some frame, one of its points lies within
3 px (squared distance <= `radius2`) of that object's point at the same frame.
"""


def tracks_by_id(tracks):
    """tracks.csv rows -> {track id: [(frame, x, y), ...]}."""
    byid = {}
    for t in tracks:
        byid.setdefault(int(t['track']), []).append((int(t['frame']), float(t['x']), float(t['y'])))
    return byid


def associate(truth, byid, radius2=9.0):
    """truth.csv rows and tracks_by_id() -> {track id: set of truth ids it came within 3 px of}."""
    at = {}
    for t in truth:
        at.setdefault(int(t['frame']), []).append((float(t['x']), float(t['y']), int(t['id'])))
    assoc = {}
    for tid, pts in byid.items():
        for fr, x, y in pts:
            for tx, ty, gid in at.get(fr, []):
                if (x - tx) ** 2 + (y - ty) ** 2 <= radius2:
                    assoc.setdefault(tid, set()).add(gid)
    return assoc


if __name__ == '__main__':
    # a self-check: track 1 passes within 3 px of object 7 at frame 2, track 2 never near
    truth = [{'frame': '2', 'x': '10', 'y': '10', 'id': '7'}, {'frame': '3', 'x': '50', 'y': '50', 'id': '8'}]
    tracks = [{'track': '1', 'frame': '2', 'x': '12', 'y': '12.2'},
              {'track': '2', 'frame': '3', 'x': '10', 'y': '10'}]
    got = associate(truth, tracks_by_id(tracks))
    assert got == {1: {7}}, got
    print('ir_diag_assoc: ok')
