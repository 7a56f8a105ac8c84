# YADE's pre-filled scene: its default engines carry labels (collider, interactionLoop, timeStepper, newton)
# that scripts use without defining them.
print('L %r %r %r' % (collider.verletDist, newton.damping, [e.label for e in O.engines]))
collider.verletDist = 0.25
newton.damping = 0.1
print('L %r %r %r' % (O.engines[1].verletDist, O.engines[-1].damping, timeStepper is O.engines[3]))
