#!/usr/bin/env python3
"""Makes the MJCF and SDF versions of the shared robots (../shared/robots) kept in this folder.

    python3 tests/robots/make_versions.py [SHARED_ROBOTS] [CHASLES]

SDF: `ign sdf -p ROBOT.urdf` (Debian's ignition-tools with libsdformat12; SDFormat 1.9). It
lumps links joined by fixed joints into their parent and drops links without mass, as
sdformat's URDF conversion does; mesh URIs become model://PACKAGE/....

MJCF: `mujoco-compile ROBOT.urdf ROBOT.xml` (Debian's libmujoco-samples, MuJoCo 2.2.2) on a
copy of the URDF without its mesh geometry: MuJoCo 2.2 reads STL meshes only, and the shared
robots carry Collada visuals and no STL. MuJoCo fuses bodies joined by fixed joints. It refuses
two of the robots as published: the ABB IRB 4600 (its tensors break the triangle inequality
and have negative moments) and the Staubli TX2-60L (no link has a mass). The ABB's MJCF is made
from the URDF as `chasles audit --fix` writes it, with the published inertials then put back
into each body as `fullinertia` (so that the MJCF carries the published defects, as the URDF
does). The Staubli's is compiled with MuJoCo's own URDF extension
`<mujoco><compiler boundmass=... boundinertia=.../></mujoco>`, which lets it compile massless
bodies; the MJCF it saves keeps the bodies without inertials, as published (MuJoCo refuses that
file, as it refuses the URDF).
"""

import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, '..', '..', '..', 'shared',
                                                             'robots')
CHASLES = sys.argv[2] if len(sys.argv) > 2 else os.path.join(HERE, '..', '..', 'build', 'bin',
                                                             'chasles')
ROBOTS = {
    'abb_irb4600': 'compas_fab/robot_library/abb_irb4600_40_255/urdf/robot_description.urdf',
    'staubli_tx2_60l': 'compas_fab/robot_library/staubli_tx2_60l/urdf/robot_description.urdf',
    'compas_ur5': 'compas_fab/robot_library/ur5_robot/urdf/robot_description.urdf',
    'double_pendulum':
        'example-robot-data/robots/double_pendulum_description/urdf/double_pendulum.urdf',
    'double_pendulum_continuous':
        'example-robot-data/robots/double_pendulum_description/urdf/double_pendulum_continuous.urdf',
    'double_pendulum_simple':
        'example-robot-data/robots/double_pendulum_description/urdf/double_pendulum_simple.urdf',
    'panda': 'example-robot-data/robots/panda_description/urdf/panda.urdf',
    'panda_collision': 'example-robot-data/robots/panda_description/urdf/panda_collision.urdf',
    'solo12': 'example-robot-data/robots/solo_description/robots/solo12.urdf',
    'ur5': 'example-robot-data/robots/ur_description/urdf/ur5_robot.urdf',
}


def strip_meshes(text):
    """The URDF without the <visual> and <collision> elements that hold a mesh."""
    return re.sub(r'<(visual|collision)\b[^>]*>(?:(?!</\1>).)*?<mesh\b(?:(?!</\1>).)*</\1>', '',
                  text, flags=re.S)


def published_inertials(urdf):
    """Each link's published inertial: (xyz, mass, ixx iyy izz ixy ixz iyz) as written."""
    out = {}
    for name, body in re.findall(r'<link\s+name="([^"]+)"\s*>(.*?)</link>', urdf, flags=re.S):
        m = re.search(r'<inertial>(.*?)</inertial>', body, flags=re.S)
        if not m:
            continue
        inertial = m.group(1)
        xyz = re.search(r'xyz="([^"]*)"', inertial).group(1)
        mass = re.search(r'<mass\s+value="([^"]*)"', inertial).group(1)
        entries = [re.search(k + r'="([^"]*)"', inertial).group(1)
                   for k in ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz')]
        out[name] = (xyz, mass, ' '.join(entries))
    return out


def restore_inertials(mjcf, inertials):
    """Each body's <inertial> replaced by the published one, as fullinertia."""
    def body(match):
        name = match.group(1)
        if name not in inertials:
            return match.group(0)
        xyz, mass, full = inertials[name]
        return re.sub(r'<inertial [^>]*/>',
                      '<inertial pos="%s" mass="%s" fullinertia="%s"/>' % (xyz, mass, full),
                      match.group(0), count=1)
    return re.sub(r'<body name="([^"]+)"[^>]*>\s*<inertial [^>]*/>', body, mjcf)


def bound_massless(urdf):
    """MuJoCo's URDF extension: bodies without mass are compiled with a floor mass and inertia."""
    return urdf.replace('</robot>', '  <mujoco><compiler boundmass="1e-6" boundinertia="1e-12"/>'
                        '</mujoco>\n</robot>')


def main():
    os.makedirs(os.path.join(HERE, 'mjcf'), exist_ok=True)
    os.makedirs(os.path.join(HERE, 'sdf'), exist_ok=True)
    for name, rel in ROBOTS.items():
        urdf_path = os.path.join(SHARED, rel)
        urdf = open(urdf_path).read()
        sdf = subprocess.run(['ign', 'sdf', '-p', urdf_path], capture_output=True, text=True,
                             check=True).stdout
        open(os.path.join(HERE, 'sdf', name + '.sdf'), 'w').write(sdf)
        with tempfile.TemporaryDirectory() as tmp:
            stripped = os.path.join(tmp, name + '.urdf')
            open(stripped, 'w').write(strip_meshes(urdf))
            if name == 'staubli_tx2_60l':
                open(stripped, 'w').write(bound_massless(strip_meshes(urdf)))
            if name == 'abb_irb4600':
                subprocess.run([CHASLES, 'audit', stripped, '--fix', '--out',
                                os.path.join(tmp, 'fixed')], capture_output=True)
                stripped = os.path.join(tmp, 'fixed', name + '.urdf')
            out = os.path.join(tmp, name + '.xml')
            log = subprocess.run(['mujoco-compile', stripped, out], capture_output=True,
                                 text=True)
            if 'Error' in log.stdout + log.stderr or not os.path.exists(out):
                print('%s: MuJoCo refuses it: %s' % (name, (log.stdout + log.stderr).strip()))
                continue
            mjcf = open(out).read()
            if name == 'abb_irb4600':
                mjcf = restore_inertials(mjcf, published_inertials(urdf))
            open(os.path.join(HERE, 'mjcf', name + '.xml'), 'w').write(mjcf)


if __name__ == '__main__':
    main()
