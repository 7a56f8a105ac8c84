# YADE reference battery for ryade's pure-Python yade.minieigen (compat/python/yade/minieigen.py).
#
#   yade -n -x yade_ref/compat/minieigen_ref.py [OUTFILE]
#
# Evaluates every expression below with YADE 2023.02a's yade.minieigenHP and writes
#   {"results": {expr: repr(result) | "ERROR:<ExceptionType>"},
#    "floats":  {expr: [float.hex of every float in the result, in iteration order]},
#    "order":   [expr, ...]}
# to OUTFILE (default: compat/tests/data/minieigen_expect.json next to this checkout).
# compat/tests/test_minieigen.py evaluates the same expressions with yade.minieigen and
# requires equal reprs and bit-identical floats.
#
# An "expression" may be several statements separated by ';': all but the last are exec'd,
# the last one is evaluated (each expression gets a fresh namespace).
# The random cases use a fixed seed and are written as literals, so the JSON is self-contained.
import copy
import json
import math
import os
import pickle
import random
import sys

STATIC = r'''
Vector3(1,2,3)
Vector3(0.1,0.2,0.3)
Vector3(-0.0,0,0)
Vector3(1e20,1e19,1e18)
Vector3(1e16,1.5e-7,123456789012345678901.0)
Vector3(1e-5,0.0001,0.0001234)
Vector3(5e-324,1e-300,1e100)
Vector3(float('inf'),float('-inf'),float('nan'))
Vector3(1/3.,2/3.,-1/7.)
Vector3()
Vector3(5)
Vector3(1,2)
Vector3(x=1,z=2)
Vector3(1.5,y=2)
Vector3(x=1,w=2)
Vector3(True,2,3)
Vector3((1,2,3))
Vector3([1,2,3])
Vector3(Vector3(1,2,3))
Vector3(Vector3i(1,2,3))
Vector3((1,2))
Vector3((1,2,3,4))
Vector3('abc')
Vector3(1,2,'a')
Vector3(1,2,None)
Vector3(10**20,2,3)
str(Vector3(1,2.5,3))
'%s'%Vector3(1,2,3)
Vector3.Zero
Vector3.Ones
Vector3.UnitX
Vector3.UnitY
Vector3.UnitZ
Vector3.Identity
Vector3.Unit(1)
Vector3.Unit(3)
Vector3.Zero is Vector3.Zero
a=Vector3.Zero; a[0]=1; (a,Vector3.Zero)
Vector3(1,2,3)[0]
Vector3(1,2,3)[2]
Vector3(1,2,3)[3]
Vector3(1,2,3)[-1]
Vector3(1,2,3)[-4]
Vector3(1,2,3)[True]
Vector3(1,2,3)[1.0]
Vector3(1,2,3)['a']
Vector3(1,2,3)[0:2]
list(Vector3(1,2,3))
tuple(Vector3(0.1,0.2,0.3))
len(Vector3(1,2,3))
2.0 in Vector3(1,2,3)
a=Vector3(1,2,3); a[0]=7; a
a=Vector3(1,2,3); a[-1]=7; a
a=Vector3(1,2,3); a[3]=7; a
a=Vector3(1,2,3); a[0]='x'; a
a=Vector3(1,2,3); a[1]=True; a
Vector3(1,2,3)+Vector3(0.1,0.2,0.3)
Vector3(1,2,3)-Vector3(0.1,0.2,0.3)
Vector3(1,2,3)+(1,1,1)
Vector3(1,2,3)+[1,1,1]
(1,1,1)+Vector3(1,2,3)
Vector3(1,2,3)+Vector3i(1,1,1)
Vector3(1,2,3)+Vector2(1,2)
Vector3(1,2,3)+1
Vector3(1,2,3)-1
Vector3(1,2,3)*2
2*Vector3(1,2,3)
Vector3(0.1,0.2,0.3)*3
3*Vector3(0.1,0.2,0.3)
Vector3(0.1,0.2,0.3)*0.1
Vector3(1,2,3)*True
Vector3(1,2,3)/2
Vector3(1,2,3)/3
Vector3(1,2,3)/0.1
Vector3(1,2,3)/0
Vector3(0,-1,2)/0
Vector3(0,-1,2)/-0.0
2/Vector3(1,2,3)
Vector3(1,2,3)*Vector3(1,2,3)
Vector3(1,2,3)/Vector3(1,2,3)
Vector3(1,2,3)*(1,1,1)
Vector3(1,2,3)*'a'
-Vector3(1,-2,0)
+Vector3(1,2,3)
Vector3(1,2,3)*1e308*10
Vector3(1,2,3)==Vector3(1,2,3)
Vector3(1,2,3)!=Vector3(1,2,3)
Vector3(1,2,3)==Vector3(1,2,3.0000000000000004)
Vector3(1,2,3)==(1,2,3)
Vector3(1,2,3)==[1,2,3]
Vector3(1,2,3)==Vector3i(1,2,3)
Vector3(1,2,3)==Vector2(1,2)
Vector3(1,2,3)==None
Vector3(1,2,3)!=None
Vector3(float('nan'),0,0)==Vector3(float('nan'),0,0)
Vector3(float('nan'),0,0)!=Vector3(float('nan'),0,0)
Vector3(-0.0,0,0)==Vector3(0,0,0)
Vector3(1,2,3)<Vector3(1,2,4)
Vector3(1,2,3).__eq__(5)
Vector3(1,2,3).__mul__(Vector3(1,2,3))
Vector3(1,2,3).__add__(5)
a=Vector3(1,2,3); b=a; a+=(1,1,1); (a, b, a is b)
a=Vector3(1,2,3); b=a; a-=Vector3(0.5,0.5,0.5); (a, b)
a=Vector3(1,2,3); b=a; a*=0.1; (a, b)
a=Vector3(1,2,3); b=a; a/=3; (a, b)
a=Vector3(1,2,3); a+=1; a
a=Vector3(1,2,3); a*=a; a
Vector3(1,2,3).dot(Vector3(4,5,6))
Vector3(1,2,3).dot((1,1,1))
Vector3(1,2,3).dot(Vector3i(1,1,1))
Vector3(1,2,3).dot(1)
Vector3(0.1,0.2,0.3).dot(Vector3(0.3,0.2,0.1))
Vector3(1e16,1,-1e16).dot(Vector3(1,1,1))
Vector3(1,1e16,-1e16).dot(Vector3(1,1,1))
Vector3(1,2,3).cross(Vector3(4,5,6))
Vector3(1,2,3).cross((1,1,1))
Vector3(1,2,3).cross(Vector3(1,2))
Vector3(0.1,0.2,0.3).cross(Vector3(0.7,-0.11,1e-3))
Vector3(1,2,3).norm()
Vector3(0.1,0.2,0.3).norm()
Vector3(0.1,0.2,0.3).squaredNorm()
Vector3(1e16,1,1).squaredNorm()
Vector3(1,1,1e16).squaredNorm()
Vector3(3e-9,4e-9,1.2e-8).norm()
Vector3(1e200,1e200,1e200).norm()
Vector3(1e-200,1e-200,1e-200).norm()
abs(Vector3(-1,2,-3))
Vector3(1,2,3).normalized()
Vector3(0.1,0.2,0.3).normalized()
Vector3(0,0,0).normalized()
Vector3(float('inf'),0,0).normalized()
Vector3(1,2,3).normalize()
a=Vector3(0.1,0.2,0.3); a.normalize(); a
a=Vector3(0,0,0); a.normalize(); a
Vector3(1,2,3).sum()
Vector3(0.1,0.2,0.3).sum()
Vector3(1e16,1,1).sum()
Vector3(1,1,1e16).sum()
Vector3(1,2,3).prod()
Vector3(0.1,0.2,0.3).prod()
Vector3(1,2,3).mean()
Vector3(0.1,0.2,0.3).mean()
Vector3(1,2,3).maxCoeff()
Vector3(1,2,3).minCoeff()
Vector3(1,-5,3).maxAbsCoeff()
Vector3(float('nan'),2,3).maxCoeff()
Vector3(2,float('nan'),3).maxCoeff()
Vector3(2,3,float('nan')).maxCoeff()
Vector3(2,float('nan'),3).minCoeff()
Vector3(-0.0,0.0,-1).maxCoeff()
Vector3(0.0,-0.0,-1).maxCoeff()
Vector3(0.0,-0.0,1).minCoeff()
Vector3(-0.0,0.0,1).minCoeff()
Vector3(1,2,3).cwiseProduct(Vector3(1,2,3))
Vector3(1,2,3).cwiseAbs()
Vector3(1,2,3).outer(Vector3(4,5,6))
Vector3(0.1,0.2,0.3).outer((0.3,0.7,1.1))
Vector3(1,2,3).asDiagonal()
Vector3(1,2,3).xy()
Vector3(1,2,3).yx()
Vector3(1,2,3).xz()
Vector3(1,2,3).zx()
Vector3(1,2,3).yz()
Vector3(1,2,3).zy()
Vector3(1,2,3).rows()
Vector3(1,2,3).cols()
Vector3(1,2,3).isApprox(Vector3(1,2,3))
Vector3(1,2,3).isApprox(Vector3(1,2,3.0000000001))
Vector3(1,2,3).isApprox(Vector3(1,2,3.00000000000001))
Vector3(1,2,3).isApprox(Vector3(1,2,3.1),0.1)
Vector3(1,2,3).__reduce__()[1:]
Vector3(0.1,0.2,0.3).__getinitargs__()
pickle.loads(pickle.dumps(Vector3(0.1,0.2,0.3)))
copy.copy(Vector3(1,2,3))
copy.deepcopy(Vector3(0.1,0.2,0.3))
a=Vector3(1,2,3); b=copy.copy(a); b[0]=9; (a,b)
type(Vector3(1,2,3)).__name__
type(Vector3(1,2,3)[0]).__name__
type(Vector3(1,2,3).norm()).__name__
type(Vector3.Random()).__name__
len(Vector3.Random())
a=Vector3(1,2,3); hash(a)==hash(a)
bool(Vector3.Zero)
Vector3i(1,2,3)
Vector3i(-3,0,7)
Vector3i()
Vector3i(5)
Vector3i((1,2,3))
Vector3i(1.5,2,3)
Vector3i(1.0,2,3)
Vector3i(Vector3(1,2,3))
Vector3i((1.0,2,3))
Vector3i(2**31,2,3)
Vector3i(-2**31-1,2,3)
Vector3i(2**31-1,2,3)
Vector3i(1,2,3)[0]
type(Vector3i(1,2,3)[0]).__name__
Vector3i(1,2,3)[-1]
Vector3i(1,2,3)+Vector3i(1,1,1)
Vector3i(1,2,3)+(1,1,1)
Vector3i(1,2,3)+Vector3(1,1,1)
Vector3i(1,2,3)-Vector3i(5,5,5)
Vector3i(1,2,3)*2
2*Vector3i(1,2,3)
Vector3i(1,2,3)*2.5
Vector3i(1,2,3)/2
-Vector3i(1,2,3)
Vector3i(2**30,2**30,2**30)*4
Vector3i(1,2,3).dot(Vector3i(1,2,3))
Vector3i(1,2,3).cross(Vector3i(4,5,6))
Vector3i(1,2,3).norm()
Vector3i(1,2,3).sum()
Vector3i(1,2,3).prod()
Vector3i(1,2,3).mean()
Vector3i(-1,-2,-2).mean()
Vector3i(1,2,3).maxCoeff()
Vector3i(1,-7,3).maxAbsCoeff()
Vector3i(1,2,3).minCoeff()
Vector3i(1,2,3).asDiagonal()
Vector3i(1,2,3).outer(Vector3i(1,2,3))
Vector3i(1,2,3).xy()
Vector3i(1,2,3)==Vector3i(1,2,3)
Vector3i(1,2,3)==(1,2,3)
Vector3i.Zero
Vector3i.Ones
Vector3i.UnitY
Vector3i(1,2,3).__reduce__()[1:]
a=Vector3i(1,2,3); a[0]=2.5; a
a=Vector3i(1,2,3); a*=2; a
Vector2(1,2)
Vector2(0.1,0.2)
Vector2(1)
Vector2((1,2))
Vector2(1,2)+Vector2(0.5,0.5)
Vector2(3,4)/2
Vector2(3,4).norm()
Vector2(0.1,0.2).norm()
Vector2(0.1,0.2).squaredNorm()
Vector2(1,2).dot((3,4))
Vector2(1,2).cross(Vector2(3,4))
Vector2(1,2).asDiagonal()
Vector2(1,2).outer(Vector2(1,2))
Vector2(1,2)==(1,2)
Vector2(1,2)[2]
Vector2.UnitX
Vector2.UnitY
Vector2.Ones
Vector2(1,2).__reduce__()[1:]
Vector2i(3,4)
Vector2i(-3,4)*3
Vector2i.Ones
Vector6(1,2,3,4,5,6)
Vector6(0.1,0.2,0.3,0.4,0.5,0.6)
Vector6(1,2,3)
Vector6((1,2,3),(4,5,6))
Vector6(Vector3(1,2,3),Vector3(4,5,6))
Vector6((1,2,3,4,5,6))
Vector6(1,2,3,4,5,6)[5]
Vector6(1,2,3,4,5,6)[6]
Vector6(1,2,3,4,5,6)[-1]
Vector6(1,2,3,4,5,6)*2
Vector6(1,2,3,4,5,6)/3
Vector6(1,2,3,4,5,6)+Vector6.Ones
Vector6(1,2,3,4,5,6).norm()
Vector6(0.1,0.2,0.3,0.4,0.5,0.6).norm()
Vector6(0.1,0.2,0.3,0.4,0.5,0.6).sum()
Vector6(0.1,0.2,0.3,0.4,0.5,0.6).normalized()
Vector6(1,2,3,4,5,6).dot(Vector6.Ones)
Vector6(0.1,0.2,0.3,0.4,0.5,0.6).dot(Vector6(0.6,0.5,0.4,0.3,0.2,0.1))
Vector6(1,2,3,4,5,6).head()
Vector6(1,2,3,4,5,6).tail()
Vector6(1,2,3,4,5,6).head(3)
Vector6(1,2,3,4,5,6).asDiagonal()
Vector6(1,2,3,4,5,6).outer(Vector6.Ones)
Vector6.Ones
Vector6.Zero
Vector6.Unit(5)
Vector6(1,2,3,4,5,6).__reduce__()[1:]
Vector6i(1,2,3,4,5,6)*2
Vector6i(1,2,3,4,5,6).head()
Vector4(1,2,3,4)
Vector4(0.1,0.2,0.3,0.4).norm()
Quaternion.Identity
Quaternion(1,2,3,4)
Quaternion(0.5,0.5,0.5,0.5)
Quaternion(0.5,-0.5,0.5,-0.5)
Quaternion(-0.5,-0.5,0.5,-0.5)
Quaternion(1,1e-17,0,0)
Quaternion(1,1e-17,1e-17,0)
Quaternion(1,3e-17,-4e-17,1.2e-16)
Quaternion(0.3,1e-300,1e-300,0)
Quaternion(0,0,0,0)
Quaternion(-1,0,0,0)
Quaternion(w=1,x=0,y=0,z=0)
Quaternion(1,2,3)
Quaternion((1,2,3,4))
str(Quaternion(1,2,3,4))
Quaternion((1,0,0),0.3)
Quaternion((1,0,0),0.5)
Quaternion((2,0,0),0.5)
Quaternion((1,1,0),0.5)
Quaternion((0,0,0),1)
Quaternion((0.2,-0.3,0.7),1.1)
Quaternion(0.5,(1,0,0))
Quaternion(1.1,Vector3(0.2,-0.3,0.7))
Quaternion(Vector3(1,0,0),0.5)
Quaternion(1.0,Vector3i(0,1,0))
Quaternion(angle=1,axis=(1,0,0))
Quaternion(axis=(1,0,0),angle=1)
Quaternion((1,0,0),float('inf'))
list(Quaternion((1,0,0),0.3))
list(Quaternion((0.2,-0.3,0.7),1.1))
list(Quaternion((2,0,0),0.5))
list(Quaternion(1.1,Vector3(0.2,-0.3,0.7)))
list(Quaternion(Vector3(1,0,0),Vector3(0,1,0)))
list(Quaternion((0.2,-0.3,0.7),(1.1,0.4,-0.2)))
list(Quaternion((1,2,3),(1,2,3)))
Quaternion(Vector3(1,0,0),Vector3(0,1,0))
Quaternion((1,0,0),(0,1,0))
Quaternion(Quaternion(1,2,3,4))
list(Quaternion(Quaternion(1,2,3,4)))
Quaternion(Matrix3.Identity)
list(Quaternion(Matrix3(0,-1,0,1,0,0,0,0,1)))
list(Quaternion(Matrix3(-1,0,0,0,-1,0,0,0,1)))
list(Quaternion(Matrix3(1,0,0,0,-1,0,0,0,-1)))
list(Quaternion(Matrix3(-1,0,0,0,1,0,0,0,-1)))
list(Quaternion(Matrix3(0.36,0.48,-0.8,-0.8,0.6,0,0.48,0.64,0.6)))
list(Quaternion(Quaternion((0.2,-0.3,0.7),2.9).toRotationMatrix()))
list(Quaternion(Quaternion((0.9,-0.3,0.1),3.1).toRotationMatrix()))
list(Quaternion(Quaternion((0.1,0.9,0.1),3.0).toRotationMatrix()))
list(Quaternion(Quaternion((0.1,0.2,0.9),3.05).toRotationMatrix()))
Quaternion(1,2,3,4)[0]
Quaternion(1,2,3,4)[3]
Quaternion(1,2,3,4)[4]
Quaternion(1,2,3,4)[-1]
len(Quaternion(1,2,3,4))
list(Quaternion(1,2,3,4))
q=Quaternion(1,2,3,4); q[0]=5; list(q)
q=Quaternion(1,2,3,4); q[3]=0.5; q
Quaternion(1,2,3,4).norm()
abs(Quaternion(1,2,3,4))
Quaternion(0.1,0.2,0.3,0.4).norm()
Quaternion(1,2,3,4).normalized()
list(Quaternion(1,2,3,4).normalized())
list(Quaternion(0.1,0.2,0.3,0.4).normalized())
q=Quaternion(0.1,0.2,0.3,0.4); q.normalize(); list(q)
Quaternion(1,2,3,4).normalize()
list(Quaternion(0,0,0,0).normalized())
Quaternion(1,2,3,4).conjugate()
list(Quaternion(1,2,3,4).conjugate())
list(Quaternion(0,0,0,0).conjugate())
Quaternion(1,2,3,4).inverse()
list(Quaternion(1,2,3,4).inverse())
list(Quaternion(0.1,0.2,0.3,0.4).inverse())
list(Quaternion(0,0,0,0).inverse())
Quaternion(1,2,3,4)*Quaternion(5,6,7,8)
list(Quaternion(1,2,3,4)*Quaternion(5,6,7,8))
list(Quaternion(0.1,0.2,0.3,0.4)*Quaternion(0.7,-0.3,0.2,0.9))
Quaternion(1,2,3,4)*Vector3(1,1,1)
Quaternion(0.1,0.2,0.3,0.4)*Vector3(0.7,-0.3,0.2)
Quaternion(1,2,3,4)*(1,1,1)
Quaternion(1,2,3,4).Rotate(Vector3(0.7,-0.3,0.2))
Quaternion(1,2,3,4).Rotate((1,2,3))
Quaternion((0.2,-0.3,0.7),1.1)*Vector3(1,2,3)
Quaternion((0.2,-0.3,0.7),1.1).Rotate(Vector3(0.1,2,-3))
Quaternion(1,2,3,4)*2
2*Quaternion(1,2,3,4)
Quaternion(1,2,3,4)+Quaternion(1,2,3,4)
Vector3(1,2,3)*Quaternion.Identity
Quaternion(1,2,3,4)==Quaternion(1,2,3,4)
Quaternion(1,2,3,4)!=Quaternion(1,2,3,4)
Quaternion(1,2,3,4)==Quaternion(1,2,3,4.0000000000001)
Quaternion(1,0,0,0)==(1,0,0,0)
Quaternion(1,0,0,0)==None
q=Quaternion(1,2,3,4); q2=q; q*=Quaternion(0.1,0.2,0.3,0.4); (list(q),list(q2))
q=Quaternion(1,2,3,4); q*=2; q
Quaternion(1,2,3,4).toAxisAngle()
Quaternion(1,2,3,4).toAngleAxis()
Quaternion((0.2,-0.3,0.7),1.1).toAxisAngle()
Quaternion(0.1,0.2,0.3,0.4).toAxisAngle()
Quaternion(-0.1,0.2,0.3,0.4).toAxisAngle()
Quaternion.Identity.toAxisAngle()
Quaternion(-1,0,0,0).toAxisAngle()
Quaternion(1,2,3,4).toRotationVector()
Quaternion((0.2,-0.3,0.7),1.1).toRotationVector()
Quaternion(1,2,3,4).toRotationMatrix()
Quaternion((1,1,1),1.0).toRotationMatrix()
Quaternion(0.1,0.2,0.3,0.4).toRotationMatrix()
Quaternion((0.2,-0.3,0.7),1.1).toRotationMatrix()
Matrix3(Quaternion(0.1,0.2,0.3,0.4))
Quaternion(1,2,3,4).angularDistance(Quaternion(1,0,0,0))
Quaternion((0.2,-0.3,0.7),1.1).angularDistance(Quaternion((0.1,0.3,0.7),0.4))
Quaternion(1,0,0,0).slerp(0.5,Quaternion(0,1,0,0))
list(Quaternion((0.2,-0.3,0.7),1.1).slerp(0.3,Quaternion((0.1,0.3,0.7),0.4)))
list(Quaternion((0.2,-0.3,0.7),1.1).slerp(0.3,Quaternion(-0.7,0.1,0.3,0.2)))
list(Quaternion(1,0,0,0).slerp(0.25,Quaternion(1,0,0,0)))
q=Quaternion(1,2,3,4); q.setFromTwoVectors(Vector3(0.2,-0.3,0.7),Vector3(1.1,0.4,-0.2)); list(q)
Quaternion(1,2,3,4).setFromTwoVectors(Vector3(1,0,0),Vector3(0,1,0))
Quaternion(1,2,3,4).__reduce__()[1:]
Quaternion(0.1,0.2,0.3,0.4).__getinitargs__()
pickle.loads(pickle.dumps(Quaternion(0.1,0.2,0.3,0.4))).__reduce__()[1:]
copy.deepcopy(Quaternion(1,2,3,4))
type(Quaternion.Identity).__name__
Matrix3.Identity
Matrix3.Zero
Matrix3.Ones
Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)
Matrix3(Vector3(1,2,3),Vector3(4,5,6),Vector3(7,8,9))
Matrix3((1,2,3),(4,5,6),(7,8,9))
Matrix3((1,2,3),(4,5,6),(7,8,9),cols=True)
Matrix3((1,2,3),(4,5,6),(7,8,9),True)
Matrix3(r0=(1,2,3),r1=(4,5,6),r2=(7,8,9),cols=True)
Matrix3(m00=1,m11=2,m22=3,m01=0,m02=0,m10=0,m12=0,m20=0,m21=0)
Matrix3(Vector3(1,2,3))
Matrix3((1,2,3))
Matrix3(Quaternion(1,2,3,4))
Matrix3(Matrix3.Identity)
Matrix3(((1,2,3),(4,5,6),(7,8,9)))
Matrix3(1,2,3)
Matrix3('a')
Matrix3(1,2,3,4,5,6,7,8,9)[0]
Matrix3(1,2,3,4,5,6,7,8,9)[2]
Matrix3(1,2,3,4,5,6,7,8,9)[3]
Matrix3(1,2,3,4,5,6,7,8,9)[-1]
Matrix3(1,2,3,4,5,6,7,8,9)[0,1]
Matrix3(1,2,3,4,5,6,7,8,9)[2,0]
Matrix3(1,2,3,4,5,6,7,8,9)[(1,2)]
Matrix3(1,2,3,4,5,6,7,8,9)[0][1]
Matrix3(1,2,3,4,5,6,7,8,9)[-1,-1]
Matrix3(1,2,3,4,5,6,7,8,9)[3,0]
Matrix3(1,2,3,4,5,6,7,8,9)[0,1,2]
Matrix3(1,2,3,4,5,6,7,8,9)[[0,1]]
len(Matrix3(1,2,3,4,5,6,7,8,9))
list(Matrix3(1,2,3,4,5,6,7,8,9))
m=Matrix3.Identity; m[0,1]=5; m
m=Matrix3.Identity; m[0]=(7,8,9); m
m=Matrix3.Identity; m[0][1]=5; m
m=Matrix3.Identity; m[3,0]=5; m
m=Matrix3.Identity; m*=2; m
m=Matrix3.Identity; n=m; m*=Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9); (m,n)
m=Matrix3.Identity; m+=Matrix3.Ones; m
m=Matrix3.Identity; m-=Matrix3.Ones; m
m=Matrix3.Identity; m/=3; m
Matrix3(1,2,3,4,5,6,7,8,9).transpose()
Matrix3(1,2,3,4,5,6,7,8,10).inverse()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,1.9).inverse()
Matrix3(1,2,3,4,5,6,7,8,9).inverse()
Matrix3.Zero.inverse()
Matrix3(1,2,3,4,5,6,7,8,9).determinant()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,1.9).determinant()
Matrix3(1,2,3,4,5,6,7,8,9).trace()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).trace()
Matrix3(1,2,3,4,5,6,7,8,9).row(1)
Matrix3(1,2,3,4,5,6,7,8,9).row(3)
Matrix3(1,2,3,4,5,6,7,8,9).col(1)
Matrix3(1,2,3,4,5,6,7,8,9).col(-1)
Matrix3(1,2,3,4,5,6,7,8,9).diagonal()
Matrix3(1,2,3,4,5,6,7,8,9).norm()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).norm()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).squaredNorm()
abs(Matrix3(1,2,3,4,5,6,7,8,9))
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).normalized()
m=Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9); m.normalize(); m
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).sum()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).prod()
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9).mean()
Matrix3(1,2,3,4,5,6,7,8,9).maxCoeff()
Matrix3(1,2,3,4,5,6,7,8,9).minCoeff()
Matrix3(1,-2,3,4,5,-16,7,8,9).maxAbsCoeff()
Matrix3(1,2,3,4,5,6,7,8,9).rows()
Matrix3(1,2,3,4,5,6,7,8,9).cols()
Matrix3(1,2,3,4,5,6,7,8,9).isApprox(Matrix3(1,2,3,4,5,6,7,8,9))
Matrix3(1,2,3,4,5,6,7,8,9)*Vector3(1,1,1)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)*Vector3(0.3,0.7,1.1)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)*(0.3,0.7,1.1)
Vector3(1,1,1)*Matrix3(1,2,3,4,5,6,7,8,9)
(1,1,1)*Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(1,2,3,4,5,6,7,8,9)*Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)*Matrix3(0.3,0.7,1.1,-0.2,0.6,0.9,0.15,-0.35,0.45)
Matrix3(1,2,3,4,5,6,7,8,9)*2
2*Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)*0.1
Matrix3(1,2,3,4,5,6,7,8,9)/2
Matrix3(1,2,3,4,5,6,7,8,9)/3
Matrix3(1,2,3,4,5,6,7,8,9)/0
Matrix3(1,2,3,4,5,6,7,8,9)+Matrix3.Identity
Matrix3(1,2,3,4,5,6,7,8,9)-Matrix3.Identity
Matrix3.Identity+((1,0,0),(0,1,0),(0,0,1))
-Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(1,2,3,4,5,6,7,8,9)*(1,2)
Matrix3(1,2,3,4,5,6,7,8,9)*Quaternion.Identity
Matrix3(1,2,3,4,5,6,7,8,9)+1
Matrix3(1,2,3,4,5,6,7,8,9)==Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3.Identity==Matrix3.Zero
Matrix3.Identity==((1,0,0),(0,1,0),(0,0,1))
Matrix3.Identity==(1,0,0,0,1,0,0,0,1)
Matrix3.Identity!=Matrix3.Zero
Matrix3(1,2,3,4,5,6,7,8,9).__reduce__()[1:]
pickle.loads(pickle.dumps(Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9)))
copy.deepcopy(Matrix3(1,2,3,4,5,6,7,8,9))
Vector3(0.2,-0.3,0.7).outer(Vector3(1.1,0.4,-0.2)).determinant()
Matrix6.Zero
Matrix6.Identity
Matrix6.Ones
Matrix6(Matrix3.Identity,Matrix3.Zero,Matrix3.Zero,Matrix3.Identity)
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9))
Matrix6(Vector6(1,2,3,4,5,6))
Matrix6(Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6))
Matrix6(Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),Vector6(1,2,3,4,5,6),cols=True)
Matrix6(1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25,26,27,28,29,30,31,32,33,34,35,36)
Matrix6.Identity[0]
Matrix6.Identity[0,0]
Matrix6.Identity[6,0]
Matrix6.Identity.row(1)
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).col(2)
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).transpose()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).ul()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).ur()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).ll()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).lr()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).trace()
Matrix6(Matrix3(1,2,3,4,5,6,7,8,9),Matrix3.Ones,Matrix3.Zero,Matrix3.Identity).diagonal()
Matrix6.Identity.trace()
Matrix6.Identity.determinant()
Matrix6.Identity.inverse()
Matrix6.Identity*Vector6.Ones
Matrix6.Identity*2
Matrix6.Identity+Matrix6.Ones
Matrix6.Identity==Matrix6.Identity
len(Matrix6.Identity)
Quaternion(u=(1,0,0),v=(0,1,0))
Quaternion((1,0,0),v=(0,1,0))
Quaternion(1,axis=(1,0,0))
Quaternion((1,0,0),angle=1)
Quaternion(foo=1,bar=2)
-Quaternion(1,2,3,4)
Quaternion(1,2,3,4).dot(Quaternion(1,2,3,4))
Quaternion(1,2,3,4)*Matrix3.Identity
Quaternion(1,2,3,4)*(1,2)
Vector3(range(3))
Vector3(x for x in (1,2,3))
Vector3({1:2})
Vector3(1,2,3)==(1,2)
Vector3(*Vector3(1,2,3))
Vector3(1,2,3) in [Vector3(0,0,0),Vector3(1,2,3)]
max(Vector3(1,5,3))
sum(Vector3(0.1,0.2,0.3))
'%g %g %g'%tuple(Vector3(0.1,2,3))
'{}'.format(Vector3(0.1,2,3))
format(Vector3(1,2,3),'.3f')
Vector3(0.1,0.2,0.3).normalized().norm()
Vector3(1,2,3).dot(Vector3(1,2,3).cross(Vector3(0.1,0.2,0.3)))
Vector3(1,2,3).norm(1)
Vector3(1,2,3).x
Vector3i(True,False,1)
Vector3i(1,2,3)*Vector3i(1,2,3)
Vector3i(1,2,3)*True
Matrix3(1,2,3,4,5,6,7,8,9)*Vector3i(1,1,1)
Matrix3(1,2,3,4,5,6,7,8,9)*[1,1,1]
Matrix3(1,2,3,4,5,6,7,8,9)*((1,0,0),(0,1,0),(0,0,1))
[r for r in Matrix3(1,2,3,4,5,6,7,8,9)]
Matrix3(1,2,3,4,5,6,7,8,9)[0]*2
m=Matrix3(1,2,3,4,5,6,7,8,9); m[1]=Vector3(0.1,0.2,0.3); m
m=Matrix3(1,2,3,4,5,6,7,8,9); m[1]=(1,2); m
m=Matrix3(1,2,3,4,5,6,7,8,9); m[1,1]='a'; m
m=Matrix3(1,2,3,4,5,6,7,8,9); m+=1; m
Matrix3(1,2,3,4,5,6,7,8,9).row(1.0)
Matrix3(1,2,3,4,5,6,7,8,9).transpose().transpose()==Matrix3(1,2,3,4,5,6,7,8,9)
Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,1.9).inverse()*Matrix3(0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,1.9)
Quaternion((0.2,-0.3,0.7),1.1).toRotationMatrix()*Vector3(1,2,3)
Quaternion((0.2,-0.3,0.7),1.1).toRotationMatrix().determinant()
Quaternion((0.2,-0.3,0.7),1.1).toRotationMatrix().transpose()*Quaternion((0.2,-0.3,0.7),1.1).toRotationMatrix()
Vector6(1,2,3,4,5,6)==(1,2,3,4,5,6)
Vector6(1,2,3,4,5,6).head()+Vector6(1,2,3,4,5,6).tail()
Matrix6.Identity.ul().determinant()
Matrix6.Identity.__len__()
'''

# Expressions whose YADE result is not bit-reproducible by design (uninitialised memory,
# random numbers, Eigen assertions) are deliberately absent: Quaternion(), Matrix3(),
# Vector2(), Vector6(), Vector.Random(), Vector3(...).pruned().


def awkward(rng):
    k = rng.random()
    if k < 0.15:
        return rng.randint(-9, 9) / 10.0
    if k < 0.25:
        return rng.randint(1, 99) / 7.0 * rng.choice((1, -1))
    return rng.uniform(-1.0, 1.0) * 10.0 ** rng.randint(-4, 4)


def generated():
    rng = random.Random(20240917)
    out = []
    a = lambda: repr(awkward(rng))
    v3 = lambda: 'Vector3(%s,%s,%s)' % (a(), a(), a())
    m3 = lambda: 'Matrix3(%s)' % ','.join(a() for _ in range(9))
    q4 = lambda: 'Quaternion(%s,%s,%s,%s)' % (a(), a(), a(), a())
    v6 = lambda: 'Vector6(%s)' % ','.join(a() for _ in range(6))
    ax = lambda: '(%s,%s,%s)' % (a(), a(), a())
    for _ in range(25):
        out.append(v3() + '.norm()')
        out.append(v3() + '.squaredNorm()')
        out.append(v3() + '.normalized()')
        out.append(v3() + '.dot(' + v3() + ')')
        out.append(v3() + '.cross(' + v3() + ')')
        out.append(v3() + '.sum()')
        out.append(v3() + '/' + a())
        out.append(m3() + '*' + v3())
    for _ in range(12):
        out.append(m3() + '*' + m3())
        out.append(m3() + '.determinant()')
        out.append(m3() + '.inverse()')
        out.append(m3() + '.norm()')
        out.append(m3() + '.sum()')
        out.append(m3() + '.trace()')
    for _ in range(20):
        out.append(q4())
        out.append('list(%s*%s)' % (q4(), q4()))
        out.append('%s*%s' % (q4(), v3()))
        out.append('list(%s.normalized())' % q4())
        out.append('list(%s.inverse())' % q4())
        out.append('%s.toRotationMatrix()' % q4())
        out.append('%s.toAxisAngle()' % q4())
        out.append('%s.norm()' % q4())
        out.append('list(Quaternion(%s,%s))' % (ax(), a()))
        out.append('Quaternion(%s,%s)' % (ax(), a()))
        out.append('list(Quaternion(%s.normalized().toRotationMatrix()))' % q4())
        out.append('list(Quaternion(%s,%s))' % (v3(), v3()))
    for _ in range(8):
        out.append(v6() + '.norm()')
        out.append(v6() + '.dot(' + v6() + ')')
        out.append(v6() + '.sum()')
        rows = ','.join(v6() for _ in range(6))
        out.append('Matrix6(%s)*%s' % (rows, v6()))
        out.append('Matrix6(%s).squaredNorm()' % rows)
        out.append('Matrix6(%s).sum()' % rows)
        out.append('Matrix6(%s).maxAbsCoeff()' % rows)
        out.append('Matrix6(%s).determinant()' % rows)
        out.append('Matrix6(%s).inverse()' % rows)
        rows2 = ','.join(v6() for _ in range(6))
        out.append('Matrix6(%s)*Matrix6(%s)' % (rows, rows2))
    return out


def floats_of(r):
    """Every float in a result, as float.hex ('nan'/'-nan' keep the sign), in iteration order."""
    if isinstance(r, bool) or isinstance(r, int) or isinstance(r, str) or r is None:
        return []
    if isinstance(r, float):
        if r != r:
            return ['-nan' if math.copysign(1.0, r) < 0 else 'nan']
        return [r.hex()]
    if isinstance(r, (tuple, list)):
        return [h for x in r for h in floats_of(x)]
    name = type(r).__name__
    if name.startswith(('Vector', 'Matrix', 'Quaternion')):
        return [h for x in r for h in floats_of(x)]
    return []


def evaluate(expr, ns):
    parts = expr.split(';')
    for stmt in parts[:-1]:
        exec(stmt.strip(), ns)
    return eval(parts[-1].strip(), ns)


def run(module_name):
    exprs = []
    seen = set()
    for e in [l for l in STATIC.strip().split('\n') if l.strip()] + generated():
        if e not in seen:
            seen.add(e)
            exprs.append(e)
    results, floats = {}, {}
    for e in exprs:
        ns = {'math': math, 'pickle': pickle, 'copy': copy}
        exec('from %s import *' % module_name, ns)
        try:
            r = evaluate(e, ns)
        except Exception as ex:
            results[e] = 'ERROR:' + type(ex).__name__
            continue
        results[e] = repr(r)
        fl = floats_of(r)
        if fl:
            floats[e] = fl
    return exprs, results, floats


if __name__ == '__main__':
    exprs, results, floats = run('yade.minieigenHP')
    here = os.path.dirname(os.path.abspath(sys.argv[0]))
    default = os.path.join(here, '..', '..', 'compat', 'tests', 'data', 'minieigen_expect.json')
    out = sys.argv[1] if len(sys.argv) > 1 else default
    with open(out + '.tmp', 'w') as f:
        json.dump({'generator': 'yade_ref/compat/minieigen_ref.py with YADE 2023.02a yade.minieigenHP',
                   'order': exprs, 'results': results, 'floats': floats}, f, indent=0, sort_keys=False)
        f.write('\n')
    os.replace(out + '.tmp', out)
    print('minieigen_ref: %d expressions -> %s' % (len(exprs), os.path.normpath(out)))
    sys.exit(0)
