#!/usr/bin/env python3
# Prints the functions of the given C++ files that are at least $MIN lines long (default 80):
# "LINES FILE FIRST_LINE", longest first. Brace matching on comment- and string-stripped text;
# lambdas count toward the function that holds them.
#   function_lengths.py --max 100   # no files: every C++ file of the project; exit 1 if any
#                                   # function is longer than 100 lines (a ctest test)
import re,sys,glob
def strip(src):
    out=[];i=0;n=len(src)
    while i<n:
        c=src[i]
        if src.startswith('//',i):
            j=src.find('\n',i); j=n if j<0 else j; out.append(' '*(j-i)); i=j
        elif src.startswith('/*',i):
            j=src.find('*/',i)+2; out.append(re.sub(r'[^\n]',' ',src[i:j])); i=j
        elif src.startswith('R"(',i):
            j=src.find(')"',i)+2; out.append(re.sub(r'[^\n]',' ',src[i:j])); i=j
        elif c=="'" and i>0 and src[i-1].isdigit():  # a digit separator: 100'000
            out.append(c); i+=1
        elif c in '"\'':
            j=i+1
            while j<n and src[j]!=c:
                j+= 2 if src[j]=='\\' else 1
            out.append(c+' '*(j-i-1)+c); i=j+1
        else: out.append(c); i+=1
    return ''.join(out)
args=sys.argv[1:]
limit=None
if args[:1]==['--max']:
    limit=int(args[1]); args=args[2:]
if not args:
    import os
    root=os.path.join(os.path.dirname(os.path.abspath(__file__)),'..')
    for d in ['core','cfd','dataset','surrogate','ste','planner','apps','tests','bench','fuzz']:
        for dp,_,fs in os.walk(os.path.join(root,d)):
            args+=[os.path.relpath(os.path.join(dp,f)) for f in sorted(fs) if f.endswith(('.cpp','.hpp'))]
res=[]
for f in args:
    s=strip(open(f).read())
    stack=[]; # (kind,startline)
    line=1; last=0
    for i,c in enumerate(s):
        if c=='\n': line+=1
        elif c=='{':
            head=s[last:i]
            kind='blk'
            infn=any(k=='fn' for k,_ in stack)
            if not infn and ')' in head and not re.search(r'\b(namespace|struct|class|enum)\b',head.split(';')[-1]) :
                kind='fn'
            stack.append((kind,line)); last=i+1
        elif c=='}':
            k,st=stack.pop(); last=i+1
            if k=='fn':
                res.append((line-st+1,f,st))
        elif c==';': last=i+1
res.sort(reverse=True)
if limit is not None:
    long=[r for r in res if r[0]>limit]
    for r in long: print('%d lines (over %d): %s:%d' % (r[0],limit,r[1],r[2]))
    print('%d functions, %d over %d lines' % (len(res),len(long),limit))
    sys.exit(1 if long else 0)
for r in res:
    if r[0]>=int(__import__('os').environ.get('MIN','80')): print(*r)
